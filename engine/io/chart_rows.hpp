// The rows of a parametric study (one table of named values per run) turned
// into chart series: an x column against one or more y columns, split into
// lines by the values of series columns.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/chart.hpp"

namespace ashlar {

// One value of a row.
struct ChartCell {
  enum class Type { number, boolean, text, other };
  Type type = Type::number;
  double number = 0.0;  // number: the value; boolean: 0 (false) or 1 (true)
  std::string text;     // text: the string; other: its type's name, e.g. "table"
};

// Column name -> value; a column the row does not have is nil.
using ChartRow = std::map<std::string, ChartCell>;

struct ChartColumns {
  std::string x;                    // plotted along x: numbers or booleans
  std::vector<std::string> y;       // one or more, each plotted as lines: numbers or booleans
  std::vector<std::string> series;  // none, or columns whose values split rows into lines
};

struct RowSeries {
  // Per y column (in the given order), per distinct combination of series
  // values (in order of those values), the points of the rows that have
  // them, sorted by x (rows with equal x keep their order). A line whose
  // rows have no finite point has no points.
  std::vector<ChartSeries> series;
  int skipped = 0;  // rows left out of at least one line: x or a y column nil, inf or NaN
  // Whether the x column, and every y column, holds booleans only (at least
  // one): their axis is labelled "false" and "true".
  bool x_boolean = false, y_boolean = false;
};

// Builds the lines of a chart from rows. Booleans count as 0 and 1. A line's
// name is its y column when there are no series columns; otherwise the
// series values "n = 16, mu = 0.5", after "y, " when there are several y
// columns. Series values are ordered numbers first (numerically), then
// false, true, then strings (their runs of digits as numbers: "case 2"
// before "case 10"), then nil (rows without the column).
// Throws InvalidArgument (messages begin "chart: ", rows counted from 1)
// for no y column, a column named twice, a column that no row has (naming
// those present), a string or another non-number in an x or y column, NaN,
// a table or the like in a series column, or no row with both x and a y.
// Points whose x or y is inf or NaN are skipped and counted. A line whose
// rows all lack a finite x or y stays, without points, named
// "<name> (no finite value)".
RowSeries series_from_rows(const std::vector<ChartRow>& rows, const ChartColumns& columns);

// The rows of a sweep over an x × y grid: each pair of an x value and a y
// value has exactly one row.
struct MapGrid {
  std::vector<double> x, y;  // the distinct values, increasing (at least 2 each)
  // z at (x[i], y[j]) is z[j * x.size() + i]; NaN: no data (z nil, NaN or
  // infinite in that row).
  std::vector<double> z;
  // Columns of booleans (0: false, 1: true); x and y then have 0 and 1.
  bool x_boolean = false, y_boolean = false, z_boolean = false;
  int no_data = 0;         // cells without a finite z
};

// The grid of rows over columns x and y with values z (numbers or booleans,
// not both). Throws InvalidArgument (messages begin "chart: map: ", rows
// counted from 1) for a column no row has, a row without a finite x or y,
// a string or table in x, y or z, fewer than 2 values of x or y, two rows at
// the same (x, y) (naming both and the pair), or a missing pair (naming the
// first, in order of x then y: the rows do not form a grid).
MapGrid grid_from_rows(const std::vector<ChartRow>& rows, const std::string& x,
                       const std::string& y, const std::string& z);

}  // namespace ashlar
