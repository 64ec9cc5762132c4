#include "study/parameter_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <map>
#include <numeric>
#include <set>

#include "core/error.hpp"

namespace ashlar::study {

namespace {

constexpr const char* kRunColumns[] = {"id", "run_status", "run_error", "run_seconds",
                                       "run_worker", "run_finished"};

// SplitMix64: a tiny generator whose output is fixed by its definition,
// unlike std::uniform_real_distribution, whose results differ between
// standard libraries.
class SampleGenerator {
public:
  explicit SampleGenerator(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  // Uniform in [0, n) without modulo bias.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    std::uint64_t r;
    do r = next();
    while (r >= limit);
    return r % n;
  }

private:
  std::uint64_t state_;
};

std::string row_text(const std::vector<std::string>& names, const std::vector<Value>& row) {
  std::string text = "{";
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i ? ", " : "") + names[i] + " = " + to_text(row[i]);
  return text + "}";
}

}  // namespace

std::string column_name_problem(const std::string& name) {
  const bool identifier =
      !name.empty() && name.size() <= 64 && !std::isdigit(static_cast<unsigned char>(name[0])) &&
      std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (!identifier)
    return "'" + name + "' is not a column name (letters, digits and _, not starting with a digit, at most 64)";
  for (const char* run_column : kRunColumns)
    if (name == run_column) return "'" + name + "' is a run column (id, run_status, run_error, run_seconds, run_worker, run_finished)";
  return "";
}

namespace {

// The fewest decimal places (0-15) that write x, to a millionth of the last
// place (what a double read from a decimal, or a step computed from them,
// keeps), or -1 when none do (a third, say).
int decimal_places(double x) {
  double scale = 1.0;
  for (int places = 0; places <= 15; ++places, scale *= 10.0) {
    const double scaled = std::abs(x) * scale;
    if (scaled >= 1e12) return -1;  // past here a millionth of the place is below the double's resolution
    if (std::abs(scaled - std::round(scaled)) <= 1e-6) return places;
  }
  return -1;
}

}  // namespace

std::vector<double> linear_range(double first, double last, int count) {
  if (!std::isfinite(first) || !std::isfinite(last))
    throw InvalidArgument("range: the ends must be finite numbers");
  if (count < 1 || (count == 1 && first != last))
    throw InvalidArgument("range: count must be at least 2 (or 1 when the ends are equal), got " +
                          std::to_string(count));
  if (count > 10'000'000) throw InvalidArgument("range: count above 10^7");
  std::vector<double> values(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i)
    values[i] = count == 1 ? first : first + (last - first) * (static_cast<double>(i) / (count - 1));
  // Ends and step written in decimals (0.08 to 0.2 in steps of 0.00025):
  // every value is the double nearest its decimal, as if typed, so that a
  // query for 0.1025 finds the row (first + 90 * step is 0.10250000000000001).
  const int places[] = {decimal_places(first), decimal_places(last),
                        count == 1 ? 0 : decimal_places((last - first) / (count - 1))};
  if (*std::min_element(std::begin(places), std::end(places)) >= 0) {
    const int decimals = *std::max_element(std::begin(places), std::end(places));
    char text[64];
    for (double& value : values) {
      std::snprintf(text, sizeof text, "%.*f", decimals, value);
      value = std::strtod(text, nullptr);
    }
  }
  values.front() = first;
  values.back() = last;
  return values;
}

ParameterRows grid(std::vector<std::pair<std::string, std::vector<Value>>> axes) {
  std::sort(axes.begin(), axes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ParameterRows result;
  std::size_t total = 1;
  for (const auto& [name, values] : axes) {
    if (values.empty()) throw InvalidArgument("params." + name + ": no values");
    result.names.push_back(name);
    total *= values.size();
    if (total > 10'000'000) throw InvalidArgument("params: the grid has more than 10^7 rows");
  }
  result.rows.reserve(total);
  std::vector<std::size_t> index(axes.size(), 0);
  for (std::size_t r = 0; r < total; ++r) {
    std::vector<Value> row;
    row.reserve(axes.size());
    for (std::size_t a = 0; a < axes.size(); ++a) row.push_back(axes[a].second[index[a]]);
    result.rows.push_back(std::move(row));
    for (std::size_t a = axes.size(); a-- > 0;) {  // the last column varies fastest
      if (++index[a] < axes[a].second.size()) break;
      index[a] = 0;
    }
  }
  return checked(std::move(result));
}

ParameterRows latin_hypercube(std::vector<SampledAxis> axes, int samples, std::uint64_t seed) {
  if (samples < 1 || samples > 10'000'000)
    throw InvalidArgument("latin_hypercube: samples must be in [1, 10^7], got " + std::to_string(samples));
  if (axes.empty()) throw InvalidArgument("latin_hypercube: no parameters");
  std::sort(axes.begin(), axes.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  SampleGenerator generator(seed);
  ParameterRows result;
  result.rows.assign(static_cast<std::size_t>(samples), {});
  for (const SampledAxis& axis : axes) {
    if (axis.levels.empty() && !(std::isfinite(axis.min) && std::isfinite(axis.max) && axis.min <= axis.max))
      throw InvalidArgument("latin_hypercube: " + axis.name + " needs finite min <= max");
    result.names.push_back(axis.name);
    std::vector<std::size_t> strata(static_cast<std::size_t>(samples));
    std::iota(strata.begin(), strata.end(), 0);
    for (std::size_t i = strata.size(); i > 1; --i) std::swap(strata[i - 1], strata[generator.below(i)]);
    for (std::size_t r = 0; r < strata.size(); ++r) {
      const double position = (static_cast<double>(strata[r]) + generator.uniform()) / samples;  // [0, 1)
      if (axis.levels.empty()) {
        result.rows[r].push_back(axis.min + (axis.max - axis.min) * position);
      } else {
        const auto level = std::min(axis.levels.size() - 1,
                                    static_cast<std::size_t>(position * static_cast<double>(axis.levels.size())));
        result.rows[r].push_back(axis.levels[level]);
      }
    }
  }
  return checked(std::move(result));
}

ParameterRows checked(ParameterRows rows) {
  if (rows.names.empty()) throw InvalidArgument("params: no parameters");
  std::set<std::string> seen;
  for (const std::string& name : rows.names) {
    if (const std::string problem = column_name_problem(name); !problem.empty())
      throw InvalidArgument("params: " + problem);
    if (!seen.insert(name).second) throw InvalidArgument("params: '" + name + "' appears twice");
  }
  std::vector<std::size_t> order(rows.names.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rows.names[a] < rows.names[b]; });
  ParameterRows sorted;
  for (std::size_t i : order) sorted.names.push_back(rows.names[i]);
  auto row_less = [](const std::vector<Value>* a, const std::vector<Value>* b) { return rows_less(*a, *b); };
  std::map<const std::vector<Value>*, std::size_t, decltype(row_less)> first_row(row_less);
  sorted.rows.reserve(rows.rows.size());
  for (std::size_t r = 0; r < rows.rows.size(); ++r) {
    const auto& row = rows.rows[r];
    if (row.size() != rows.names.size())
      throw InvalidArgument("params: row " + std::to_string(r + 1) + " has " + std::to_string(row.size()) +
                            " values for " + std::to_string(rows.names.size()) + " parameters");
    std::vector<Value> reordered;
    for (std::size_t i : order) {
      if (std::holds_alternative<std::monostate>(row[i]))
        throw InvalidArgument("params: row " + std::to_string(r + 1) + " has no value for '" + rows.names[i] + "'");
      if (const auto* d = std::get_if<double>(&row[i]); d && std::isnan(*d))
        throw InvalidArgument("params: row " + std::to_string(r + 1) + ": '" + rows.names[i] + "' is NaN");
      reordered.push_back(row[i]);
    }
    sorted.rows.push_back(std::move(reordered));
  }
  for (std::size_t r = 0; r < sorted.rows.size(); ++r) {
    const auto [it, inserted] = first_row.emplace(&sorted.rows[r], r);
    if (!inserted)
      throw InvalidArgument("params: rows " + std::to_string(it->second + 1) + " and " + std::to_string(r + 1) +
                            " are the same, " + row_text(sorted.names, sorted.rows[r]));
  }
  if (sorted.rows.empty()) throw InvalidArgument("params: no rows");
  return sorted;
}

}  // namespace ashlar::study
