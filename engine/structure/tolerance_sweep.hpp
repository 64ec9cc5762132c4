// Contacts across a range of tolerances, for choosing one: how many joints
// each finds, which pairs interpenetrate or float, and the range where the
// contact set does not change.
#pragma once

#include <vector>

#include "structure/structure.hpp"

namespace ashlar {

struct ToleranceRow {
  double tolerance = 0.0;  // m
  int interfaces = 0;
  int pairs = 0;      // block pairs in contact
  int new_pairs = 0;  // pairs in contact here and not at the previous (smaller) tolerance
  int lost_pairs = 0; // pairs in contact at the previous tolerance and not here
  int overlaps = 0;   // pairs refused as interpenetrating (Structure::overlaps)
  int floating = 0;   // free blocks with no chain of contacts to a support
  int warped = 0;     // blocks with a face warped beyond the tolerance (Block::warp)
};

struct ToleranceSweep {
  std::vector<ToleranceRow> rows;  // by increasing tolerance
  // The widest range (by hi / lo) of consecutive rows with one contact set
  // (no pair gained or lost), no overlap and no floating block: tolerances
  // in it give the same analysis. lo = hi = 0 when no row qualifies.
  double lo = 0.0, hi = 0.0;
  double suggested = 0.0;  // m: the geometric mean of lo and hi
};

// The rows for `tolerances` (m, > 0, increasing; options' tolerance is
// replaced by each). Throws InvalidArgument for an empty or unsorted list.
ToleranceSweep sweep_contact_tolerance(const Structure& structure, const ContactOptions& options,
                                       const std::vector<double>& tolerances);

// The default candidates: `count` tolerances spaced evenly in logarithm
// from 1e-4 to 0.2 times the median size of the free blocks (block_size).
std::vector<double> default_sweep_tolerances(const Structure& structure, int count = 19);

}  // namespace ashlar
