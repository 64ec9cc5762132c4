// The parameter rows of a study: a full grid, explicit rows, or a Latin
// hypercube sample. Every generator is deterministic (the same arguments
// give the same rows on every machine), which is what lets a killed study
// resume and lets MPI ranks agree on the rows.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "study/study_value.hpp"

namespace ashlar::study {

struct ParameterRows {
  std::vector<std::string> names;          // one per column, sorted by name
  std::vector<std::vector<Value>> rows;    // rows × names.size()
};

// `count` numbers from first to last, evenly spaced, both ends exact. When
// the ends and the step are decimals of at most 15 places, each number is
// the double nearest its decimal (0.1025, as typed, not 0.10250000000000001).
// count >= 2, or 1 when first == last. Throws InvalidArgument otherwise or for
// non-finite ends.
std::vector<double> linear_range(double first, double last, int count);

// Every combination of the axes' values. Columns are sorted by name; the
// first column varies slowest. Each axis needs at least one value.
ParameterRows grid(std::vector<std::pair<std::string, std::vector<Value>>> axes);

// One axis of a Latin hypercube: a continuous interval [min, max], or a list
// of levels (any values) chosen by stratified index.
struct SampledAxis {
  std::string name;
  double min = 0.0, max = 0.0;  // used when levels is empty
  std::vector<Value> levels;
};

// `samples` rows; on every axis each of the `samples` equal strata holds
// exactly one row, placed uniformly at random inside it (a level axis maps
// the stratum position onto its levels). samples in [1, 10^7].
ParameterRows latin_hypercube(std::vector<SampledAxis> axes, int samples, std::uint64_t seed);

// Checks the rows of a study and puts the columns in name order: names are
// identifiers ([A-Za-z_][A-Za-z0-9_]*, at most 64 characters) and not one of
// the run columns (id, run_status, run_error, run_seconds, run_worker,
// run_finished); every row has a value for every name; no nil values; no two
// rows alike. Throws InvalidArgument naming the offending name or row (1-based).
ParameterRows checked(ParameterRows rows);

// Whether `name` may name a returned field (the identifier rule above);
// an empty string when it may, otherwise why not.
std::string column_name_problem(const std::string& name);

}  // namespace ashlar::study
