#include "io/chart_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {
namespace {

// A row's values in the series columns; nullptr for nil.
using SeriesKey = std::vector<const ChartCell*>;

const ChartCell* find_cell(const ChartRow& row, const std::string& column) {
  const auto found = row.find(column);
  return found == row.end() ? nullptr : &found->second;
}

std::string number_text(double value) {
  // As Lua's tostring writes numbers: 16, 0.5, 1e-05.
  char text[32];
  std::snprintf(text, sizeof text, "%.14g", value);
  return text;
}

std::string value_text(const ChartCell* cell) {
  if (!cell) return "nil";
  switch (cell->type) {
    case ChartCell::Type::number:
      return number_text(cell->number);
    case ChartCell::Type::boolean:
      return cell->number != 0.0 ? "true" : "false";
    case ChartCell::Type::text:
      return cell->text;
    case ChartCell::Type::other:
      break;
  }
  return cell->text;
}

// Numbers, then booleans, then strings, then nil.
int rank(const ChartCell* cell) {
  if (!cell) return 3;
  switch (cell->type) {
    case ChartCell::Type::number:
      return 0;
    case ChartCell::Type::boolean:
      return 1;
    default:
      return 2;
  }
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Compares strings with their runs of digits taken as whole numbers, so that
// "case 2" comes before "case 10": < 0, 0 or > 0.
int natural_compare(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (!is_digit(a[i]) || !is_digit(b[j])) {
      if (a[i] != b[j])
        return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]) ? -1 : 1;
      ++i;
      ++j;
      continue;
    }
    const auto number_at = [](const std::string& text, size_t& at) {
      while (at < text.size() && text[at] == '0') ++at;  // leading zeros do not count
      const size_t start = at;
      while (at < text.size() && is_digit(text[at])) ++at;
      return text.substr(start, at - start);
    };
    const std::string x = number_at(a, i), y = number_at(b, j);
    if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;
    if (x != y) return x < y ? -1 : 1;
  }
  return (a.size() - i > b.size() - j) - (a.size() - i < b.size() - j);
}

bool value_less(const ChartCell* a, const ChartCell* b) {
  if (rank(a) != rank(b)) return rank(a) < rank(b);
  if (!a) return false;
  if (a->type == ChartCell::Type::text) {
    // Strings equal but for leading zeros ("07", "7") stay apart.
    const int order = natural_compare(a->text, b->text);
    return order != 0 ? order < 0 : a->text < b->text;
  }
  return a->number < b->number;
}

struct KeyLess {
  bool operator()(const SeriesKey& a, const SeriesKey& b) const {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), value_less);
  }
};

void check_listed_once(const std::vector<std::string>& names, const char* role) {
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (!seen.insert(name).second) {
      throw InvalidArgument(std::string("chart: ") + role + ": column '" + name +
                            "' is listed twice");
    }
  }
}

void check_present(const std::string& column, const char* role,
                   const std::set<std::string>& present) {
  if (present.count(column)) return;
  const std::vector<std::string> names(present.begin(), present.end());
  throw InvalidArgument(std::string("chart: ") + role + ": no row has a column '" + column + "' (" +
                        (names.empty() ? "the rows have no columns" : "columns: " + join(names)) +
                        ")");
}

std::string cell_kind(const ChartCell& cell) {
  return cell.type == ChartCell::Type::text ? "a string (\"" + cell.text + "\")" : "a " + cell.text;
}

// x and y cells: numbers or booleans (points with a value that is not
// finite are skipped, as rows without one).
void check_plotted(const ChartCell* cell, const std::string& column, const char* role, size_t row) {
  if (!cell) return;
  const std::string where = std::string("chart: ") + role + ": row " + std::to_string(row + 1);
  if (cell->type == ChartCell::Type::text || cell->type == ChartCell::Type::other) {
    throw InvalidArgument(where + " has " + cell_kind(*cell) + " in column '" + column +
                          "'; plotted columns take numbers or booleans");
  }
}

// Series cells: numbers but NaN (math.huge is a value: no sliding),
// booleans or strings.
void check_series_value(const ChartCell* cell, const std::string& column, size_t row) {
  if (!cell) return;
  const std::string where = "chart: series: row " + std::to_string(row + 1);
  if (cell->type == ChartCell::Type::other) {
    throw InvalidArgument(where + " has a " + cell->text + " in column '" + column +
                          "'; series columns take numbers, booleans or strings");
  }
  if (cell->type == ChartCell::Type::number && std::isnan(cell->number)) {
    throw InvalidArgument(where + " has " + column + " = nan; series values must be numbers, booleans or strings");
  }
}

std::string series_name(const std::string& y, const SeriesKey& key, const ChartColumns& columns) {
  if (columns.series.empty()) return y;
  std::vector<std::string> parts;
  for (size_t k = 0; k < key.size(); ++k) {
    parts.push_back(columns.series[k] + " = " + value_text(key[k]));
  }
  return (columns.y.size() > 1 ? y + ", " : "") + join(parts);
}

// Whether the columns' values are booleans only, at least one.
bool only_booleans(const std::vector<ChartRow>& rows, const std::vector<std::string>& columns) {
  bool any = false;
  for (const ChartRow& row : rows) {
    for (const std::string& column : columns) {
      const ChartCell* cell = find_cell(row, column);
      if (!cell) continue;
      if (cell->type != ChartCell::Type::boolean) return false;
      any = true;
    }
  }
  return any;
}

}  // namespace

RowSeries series_from_rows(const std::vector<ChartRow>& rows, const ChartColumns& columns) {
  if (columns.y.empty()) throw InvalidArgument("chart: y: expected at least one column");
  check_listed_once(columns.y, "y");
  check_listed_once(columns.series, "series");
  if (rows.empty()) throw InvalidArgument("chart: nothing to plot: data has no rows");
  std::set<std::string> present;
  for (const ChartRow& row : rows) {
    for (const auto& entry : row) present.insert(entry.first);
  }
  check_present(columns.x, "x", present);
  for (const std::string& y : columns.y) check_present(y, "y", present);
  for (const std::string& s : columns.series) check_present(s, "series", present);
  for (size_t r = 0; r < rows.size(); ++r) {
    check_plotted(find_cell(rows[r], columns.x), columns.x, "x", r);
    for (const std::string& y : columns.y) check_plotted(find_cell(rows[r], y), y, "y", r);
    for (const std::string& s : columns.series) check_series_value(find_cell(rows[r], s), s, r);
  }

  RowSeries result;
  result.x_boolean = only_booleans(rows, {columns.x});
  result.y_boolean = only_booleans(rows, columns.y);
  std::vector<bool> skipped(rows.size(), false);
  bool any_point = false;
  for (const std::string& y : columns.y) {
    // Every series value of a row with this y column has a line, points or not.
    std::map<SeriesKey, std::vector<Vec2>, KeyLess> lines;
    for (size_t r = 0; r < rows.size(); ++r) {
      const ChartCell* x_cell = find_cell(rows[r], columns.x);
      const ChartCell* y_cell = find_cell(rows[r], y);
      SeriesKey key;
      for (const std::string& s : columns.series) key.push_back(find_cell(rows[r], s));
      std::vector<Vec2>& points = lines[key];
      if (!x_cell || !y_cell || !std::isfinite(x_cell->number) || !std::isfinite(y_cell->number)) {
        skipped[r] = true;
        continue;
      }
      points.emplace_back(x_cell->number, y_cell->number);
      any_point = true;
    }
    for (auto& [key, points] : lines) {
      std::stable_sort(points.begin(), points.end(),
                       [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); });
      const std::string name = series_name(y, key, columns);
      result.series.push_back(
          {points.empty() ? name + " (no finite value)" : name, std::move(points)});
    }
  }
  result.skipped = static_cast<int>(std::count(skipped.begin(), skipped.end(), true));
  if (!any_point) {
    throw InvalidArgument("chart: nothing to plot: no row has both x ('" + columns.x +
                          "') and y ('" + join(columns.y) + "'); " +
                          std::to_string(result.skipped) + " rows skipped");
  }
  return result;
}

}  // namespace ashlar

namespace ashlar {

MapGrid grid_from_rows(const std::vector<ChartRow>& rows, const std::string& x,
                       const std::string& y, const std::string& z) {
  if (rows.empty()) throw InvalidArgument("chart: map: nothing to plot: data has no rows");
  std::set<std::string> present;
  for (const ChartRow& row : rows) {
    for (const auto& entry : row) present.insert(entry.first);
  }
  check_present(x, "x", present);
  check_present(y, "y", present);
  check_present(z, "z", present);
  bool numbers = false, booleans = false;
  for (size_t r = 0; r < rows.size(); ++r) {
    const ChartCell* x_cell = find_cell(rows[r], x);
    const ChartCell* y_cell = find_cell(rows[r], y);
    const ChartCell* z_cell = find_cell(rows[r], z);
    check_plotted(x_cell, x, "map: x", r);
    check_plotted(y_cell, y, "map: y", r);
    check_plotted(z_cell, z, "map: z", r);
    for (const auto& [cell, column] : {std::pair{x_cell, &x}, std::pair{y_cell, &y}}) {
      if (!cell || !std::isfinite(cell->number)) {
        throw InvalidArgument("chart: map: row " + std::to_string(r + 1) + " has no finite " +
                              *column + " (" + value_text(cell) +
                              "); every row of a map sits at a point of the grid");
      }
    }
    if (z_cell) (z_cell->type == ChartCell::Type::boolean ? booleans : numbers) = true;
  }
  if (numbers && booleans) {
    throw InvalidArgument("chart: map: z: column '" + z +
                          "' holds both numbers and booleans; a map takes one or the other");
  }
  MapGrid grid;
  grid.z_boolean = booleans;
  grid.x_boolean = only_booleans(rows, {x});
  grid.y_boolean = only_booleans(rows, {y});
  std::set<double> xs, ys;
  for (const ChartRow& row : rows) {
    xs.insert(find_cell(row, x)->number);
    ys.insert(find_cell(row, y)->number);
  }
  grid.x.assign(xs.begin(), xs.end());
  grid.y.assign(ys.begin(), ys.end());
  for (const auto& [values, column] : {std::pair{&grid.x, &x}, std::pair{&grid.y, &y}}) {
    if (values->size() < 2) {
      throw InvalidArgument("chart: map: " + *column + " has " + std::to_string(values->size()) +
                            " value; a map needs at least 2 along each axis");
    }
  }
  const size_t nx = grid.x.size();
  const auto index = [](const std::vector<double>& values, double value) {
    return static_cast<size_t>(std::lower_bound(values.begin(), values.end(), value) -
                               values.begin());
  };
  const auto pair_text = [&](double a, double b) {
    return "(" + x + " = " + number_text(a) + ", " + y + " = " + number_text(b) + ")";
  };
  std::vector<size_t> row_at(nx * grid.y.size(), rows.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    const double a = find_cell(rows[r], x)->number, b = find_cell(rows[r], y)->number;
    size_t& at = row_at[index(grid.y, b) * nx + index(grid.x, a)];
    if (at != rows.size()) {
      throw InvalidArgument("chart: map: rows " + std::to_string(at + 1) + " and " +
                            std::to_string(r + 1) + " are both at " + pair_text(a, b) +
                            "; a map takes one row per point of the grid");
    }
    at = r;
  }
  for (size_t i = 0; i < nx; ++i) {
    for (size_t j = 0; j < grid.y.size(); ++j) {
      if (row_at[j * nx + i] != rows.size()) continue;
      throw InvalidArgument("chart: map: the rows do not form a grid: no row at " +
                            pair_text(grid.x[i], grid.y[j]) + " (" + std::to_string(nx) + " " +
                            x + " values × " + std::to_string(grid.y.size()) + " " + y +
                            " values, " + std::to_string(rows.size()) + " rows)");
    }
  }
  grid.z.resize(row_at.size());
  for (size_t k = 0; k < row_at.size(); ++k) {
    const ChartCell* cell = find_cell(rows[row_at[k]], z);
    grid.z[k] = cell && std::isfinite(cell->number) ? cell->number
                                                     : std::numeric_limits<double>::quiet_NaN();
    if (std::isnan(grid.z[k])) ++grid.no_data;
  }
  if (grid.no_data == static_cast<int>(grid.z.size())) {
    throw InvalidArgument("chart: map: nothing to plot: no row has a finite z ('" + z + "')");
  }
  return grid;
}

}  // namespace ashlar
