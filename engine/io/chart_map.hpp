// Maps of a study over an x × y grid (stability maps): each grid point's
// cell filled with the colour of its z, a colour bar, and a boundary line:
// between false and true cells for a boolean z, a contour for a number z.
// Drawn by PLplot like the charts (io/chart.hpp); .png, .svg or .pdf.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/chart.hpp"
#include "io/chart_rows.hpp"

namespace ashlar {

struct MapSpec {
  MapGrid grid;  // from grid_from_rows
  // Number z: the values where the colours change, increasing, at least 3:
  // the map shows the bands between them (values outside take the end
  // bands' colours). Empty: colours vary continuously over value_range(z)
  // (from 0 when no value is negative).
  std::vector<double> levels;
  // Number z: a contour line at this value, linear between grid points.
  // A boolean z always has its boundary: the cell edges between false and
  // true cells.
  std::optional<double> boundary;
  // Reference curves drawn dashed over the cells (a closed form to compare
  // the boundary with, say): polylines of at least 2 finite points in data
  // units, cut off at the plot's frame.
  std::vector<std::vector<Vec2>> curves;
  std::string map = "viridis";  // number z: one of color_map_names()
  std::string title;            // above the plot; none when empty
  std::string x_label, y_label, z_label;  // axes and colour bar; none when empty
  int width = 900, height = 600;          // as ChartSpec's
};

struct MapDrawing {
  // The plot area and its axes, which end at the outer cells' edges.
  ChartFrame frame;
  double lo = 0.0, hi = 1.0;  // z at the colour bar's ends (0 and 1 for booleans)
  // The boundary as drawn: polylines in data units.
  std::vector<std::vector<Vec2>> boundary;
};

// The edges of the cells around values (increasing, at least 2): halfway
// between neighbours, half a step beyond the ends; values.size() + 1 of them.
std::vector<double> cell_edges(const std::vector<double>& values);

// The boundary of spec's map as polylines (segments joined where they meet):
// for a boolean z the cell edges between a false and a true cell (cells
// without data have none); for a number z with spec.boundary the contour at
// that value by marching squares between the grid points (linear along
// their edges; a saddle is split as the mean of its corners says), over
// squares whose four corners have data. Empty otherwise.
std::vector<std::vector<Vec2>> map_boundary(const MapSpec& spec);

// Draws the map and writes it atomically to path: the cells (no data: light
// grey), the boundary in black over them, the framed axes with PLplot's
// ticks ("false"/"true" on an axis of booleans), the colour bar right of
// the plot with its label, the title. Throws InvalidArgument for an unknown
// extension or colour map, a size outside [200, 16384], levels that are
// fewer than 3 or not increasing, levels or boundary with a boolean z, or a
// non-finite boundary; IoError when PLplot fails or the file cannot be
// written.
MapDrawing draw_map(const std::string& path, const MapSpec& spec);

}  // namespace ashlar
