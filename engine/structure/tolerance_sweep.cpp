#include "structure/tolerance_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "core/error.hpp"
#include "core/union_find.hpp"
#include "structure/contact_detection.hpp"
#include "structure/overlap_detection.hpp"

namespace ashlar {

ToleranceSweep sweep_contact_tolerance(const Structure& structure, const ContactOptions& options,
                                       const std::vector<double>& tolerances) {
  if (tolerances.empty()) throw InvalidArgument("tolerance sweep: no tolerance given");
  for (size_t k = 0; k < tolerances.size(); ++k) {
    if (!(std::isfinite(tolerances[k]) && tolerances[k] > 0.0) || (k > 0 && !(tolerances[k] > tolerances[k - 1]))) {
      throw InvalidArgument("tolerance sweep: tolerances must be finite, > 0 and increasing (m), got " +
                            std::to_string(tolerances[k]) + " at position " + std::to_string(k + 1));
    }
  }
  const std::vector<const Block*> blocks = structure.block_pointers();
  ToleranceSweep sweep;
  std::vector<std::set<std::pair<int, int>>> pair_sets;
  for (double tolerance : tolerances) {
    ContactOptions at = options;
    at.tolerance = tolerance;
    const std::vector<Interface> found = detect_interfaces(blocks, at);
    ToleranceRow row;
    row.tolerance = tolerance;
    row.interfaces = static_cast<int>(found.size());
    std::set<std::pair<int, int>> pairs;
    UnionFind held(blocks.size() + 1);  // item blocks.size(): the ground
    const int ground = static_cast<int>(blocks.size());
    for (int i = 0; i < structure.size(); ++i) {
      if (structure.is_support(i)) held.join(i, ground);
      if (blocks[i]->warp() > tolerance) ++row.warped;
    }
    for (const Interface& contact : found) {
      pairs.emplace(contact.a, contact.b);
      held.join(contact.a, contact.b);
    }
    for (int i = 0; i < structure.size(); ++i) {
      if (held.root(i) != held.root(ground)) ++row.floating;
    }
    row.pairs = static_cast<int>(pairs.size());
    if (!pair_sets.empty()) {
      const std::set<std::pair<int, int>>& before = pair_sets.back();
      for (const auto& pair : pairs) row.new_pairs += before.count(pair) ? 0 : 1;
      for (const auto& pair : before) row.lost_pairs += pairs.count(pair) ? 0 : 1;
    }
    row.overlaps = static_cast<int>(detect_overlaps(blocks, tolerance).size());
    pair_sets.push_back(std::move(pairs));
    sweep.rows.push_back(row);
  }
  // The widest run of usable rows whose contact set does not change.
  double best = 0.0;
  for (size_t first = 0; first < sweep.rows.size(); ++first) {
    const auto usable = [&](size_t k) { return sweep.rows[k].overlaps == 0 && sweep.rows[k].floating == 0; };
    if (!usable(first)) continue;
    size_t last = first;
    while (last + 1 < sweep.rows.size() && usable(last + 1) && pair_sets[last + 1] == pair_sets[first]) ++last;
    const double width = sweep.rows[last].tolerance / sweep.rows[first].tolerance;
    if (width > best) {
      best = width;
      sweep.lo = sweep.rows[first].tolerance;
      sweep.hi = sweep.rows[last].tolerance;
    }
  }
  if (best > 0.0) sweep.suggested = std::sqrt(sweep.lo * sweep.hi);
  return sweep;
}

std::vector<double> default_sweep_tolerances(const Structure& structure, int count) {
  std::vector<double> sizes;
  for (int i = 0; i < structure.size(); ++i) {
    if (!structure.is_support(i)) sizes.push_back(block_size(structure.block(i)));
  }
  if (sizes.empty()) {
    for (int i = 0; i < structure.size(); ++i) sizes.push_back(block_size(structure.block(i)));
  }
  if (sizes.empty()) throw InvalidArgument("tolerance sweep: the structure has no blocks");
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  const double size = sizes[sizes.size() / 2];
  std::vector<double> tolerances;
  for (int k = 0; k < count; ++k) {
    tolerances.push_back(1e-4 * size * std::pow(0.2 / 1e-4, count > 1 ? double(k) / (count - 1) : 0.0));
  }
  return tolerances;
}

}  // namespace ashlar
