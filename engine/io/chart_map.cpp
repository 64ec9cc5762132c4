// Maps through PLplot (io/plplot_picture): the cells are filled polygons
// (plfill) in colour map 1, set from the colour map's colours (or the two
// colours of false and true); the colour bar is plcolorbar's, a gradient
// for continuous colours, shades for bands and booleans, so that bar and
// cells take their colours from the same map. As in io/chart.cpp,
// everything is prepared first and one painter makes the PLplot calls.
#include "io/chart_map.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/chart_layout.hpp"
#include "io/color_map.hpp"
#include "io/image_format.hpp"
#include "io/plplot_picture.hpp"

namespace ashlar {
namespace {

constexpr int kMinImageSize = 200;
// The maps are piecewise linear over at most 17 control points; 65 evenly
// spaced ones reproduce them to well under an 8-bit step (as the legends).
constexpr int kColorPoints = 65;

// Cells of false and true: the Okabe-Ito vermillion and blue, halfway to
// white, so that the boundary and the frame stand out on them.
const Rgb kFalseColor{(213 / 255.0 + 1.0) / 2, (94 / 255.0 + 1.0) / 2, 0.5};
const Rgb kTrueColor{0.5, (114 / 255.0 + 1.0) / 2, (178 / 255.0 + 1.0) / 2};
const Rgb kNoDataColor{0.85, 0.85, 0.85};
const Rgb kBoundaryColor{0.0, 0.0, 0.0};

enum ColorIndex : PLINT { kBackground, kText, kNoData, kBoundary, kColorCount };

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

using Segment = std::pair<Vec2, Vec2>;

// Segments joined into polylines where their ends meet exactly (the
// boundary's segments share the coordinates of their common points).
std::vector<std::vector<Vec2>> joined(const std::vector<Segment>& segments) {
  std::vector<std::vector<Vec2>> lines;
  std::vector<bool> used(segments.size(), false);
  for (size_t first = 0; first < segments.size(); ++first) {
    if (used[first]) continue;
    used[first] = true;
    std::vector<Vec2> line{segments[first].first, segments[first].second};
    // Grow the line at its end, then (reversed) at its other end.
    for (int side = 0; side < 2; ++side) {
      for (bool grown = true; grown;) {
        grown = false;
        for (size_t k = 0; k < segments.size() && !grown; ++k) {
          if (used[k]) continue;
          const auto& [a, b] = segments[k];
          if (a != line.back() && b != line.back()) continue;
          line.push_back(a == line.back() ? b : a);
          used[k] = true;
          grown = true;
        }
      }
      std::reverse(line.begin(), line.end());
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

// The cell edges between false and true cells of a boolean grid.
std::vector<Segment> boolean_boundary(const MapGrid& grid) {
  const std::vector<double> ex = cell_edges(grid.x), ey = cell_edges(grid.y);
  const size_t nx = grid.x.size(), ny = grid.y.size();
  const auto z = [&](size_t i, size_t j) { return grid.z[j * nx + i]; };
  const auto differ = [](double a, double b) { return !std::isnan(a) && !std::isnan(b) && a != b; };
  std::vector<Segment> segments;
  for (size_t j = 0; j < ny; ++j) {
    for (size_t i = 0; i < nx; ++i) {
      if (i + 1 < nx && differ(z(i, j), z(i + 1, j))) {
        segments.push_back({{ex[i + 1], ey[j]}, {ex[i + 1], ey[j + 1]}});
      }
      if (j + 1 < ny && differ(z(i, j), z(i, j + 1))) {
        segments.push_back({{ex[i], ey[j + 1]}, {ex[i + 1], ey[j + 1]}});
      }
    }
  }
  return segments;
}

// The contour at `level` of a number grid, by marching squares.
std::vector<Segment> contour(const MapGrid& grid, double level) {
  const size_t nx = grid.x.size(), ny = grid.y.size();
  std::vector<Segment> segments;
  for (size_t j = 0; j + 1 < ny; ++j) {
    for (size_t i = 0; i + 1 < nx; ++i) {
      // Corners counter-clockwise from the lower left.
      const size_t ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      double z[4];
      bool above[4];
      bool complete = true;
      for (int c = 0; c < 4; ++c) {
        z[c] = grid.z[cj[c] * nx + ci[c]];
        complete = complete && !std::isnan(z[c]);
        above[c] = z[c] >= level;
      }
      if (!complete) continue;
      // The crossing on edge e (corners e and e + 1), computed from the
      // corner with the lower grid index so that both squares sharing the
      // edge get the same point.
      const auto crossing = [&](int e) {
        int a = e, b = (e + 1) % 4;
        if (cj[b] < cj[a] || (cj[b] == cj[a] && ci[b] < ci[a])) std::swap(a, b);
        const double w = (level - z[a]) / (z[b] - z[a]);
        return Vec2(grid.x[ci[a]] + w * (grid.x[ci[b]] - grid.x[ci[a]]),
                    grid.y[cj[a]] + w * (grid.y[cj[b]] - grid.y[cj[a]]));
      };
      std::vector<int> crossed;
      for (int e = 0; e < 4; ++e) {
        if (above[e] != above[(e + 1) % 4]) crossed.push_back(e);
      }
      if (crossed.size() == 2) {
        // Corners on the level give segments of no length: left out.
        const Segment segment{crossing(crossed[0]), crossing(crossed[1])};
        if (segment.first != segment.second) segments.push_back(segment);
      } else if (crossed.size() == 4) {
        // A saddle: the mean of the corners says which pair of corners the
        // lines cut off.
        const bool centre_above = (z[0] + z[1] + z[2] + z[3]) / 4 >= level;
        if (centre_above == above[0]) {
          segments.push_back({crossing(0), crossing(1)});  // around corner 1
          segments.push_back({crossing(2), crossing(3)});  // around corner 3
        } else {
          segments.push_back({crossing(3), crossing(0)});  // around corner 0
          segments.push_back({crossing(1), crossing(2)});  // around corner 2
        }
      }
    }
  }
  return segments;
}

void check_map(const MapSpec& spec) {
  check_image_size(spec.width, spec.height, kMinImageSize, "chart");
  const MapGrid& grid = spec.grid;
  if (grid.x.size() < 2 || grid.y.size() < 2 || grid.z.size() != grid.x.size() * grid.y.size()) {
    throw InvalidArgument("chart: map: the grid needs at least 2 x and 2 y values and one z each");
  }
  if (grid.z_boolean && (!spec.levels.empty() || spec.boundary)) {
    throw InvalidArgument(std::string("chart: map: ") + (spec.boundary ? "boundary" : "levels") +
                          " takes a z of numbers; a boolean z is coloured false and true, with "
                          "the boundary between them");
  }
  if (!spec.levels.empty()) {
    bool increasing = spec.levels.size() >= 3;
    for (size_t k = 0; k < spec.levels.size(); ++k) {
      increasing = increasing && std::isfinite(spec.levels[k]) &&
                   (k == 0 || spec.levels[k] > spec.levels[k - 1]);
    }
    if (!increasing) {
      std::string values;
      for (const double level : spec.levels) values += (values.empty() ? "" : ", ") + number_text(level);
      throw InvalidArgument("chart: map: levels must be at least 3 finite increasing values, got {" +
                            values + "}");
    }
  }
  for (size_t k = 0; k < spec.curves.size(); ++k) {
    const std::vector<Vec2>& curve = spec.curves[k];
    if (curve.size() < 2 || std::any_of(curve.begin(), curve.end(), [](const Vec2& p) { return !p.allFinite(); })) {
      throw InvalidArgument("chart: map: curve " + std::to_string(k + 1) +
                            " must have at least 2 points, each of finite numbers");
    }
  }
  if (spec.boundary && !std::isfinite(*spec.boundary)) {
    throw InvalidArgument("chart: map: boundary must be a finite value of z, got " +
                          number_text(*spec.boundary));
  }
  check_color_map(spec.map);
}

// Everything the PLplot calls need, in their types.
struct PreparedMap {
  ChartMetrics metrics{kMinImageSize, kMinImageSize};
  PLINT width = 0, height = 0;
  std::vector<PLFLT> ex, ey;  // cell edges
  // Per cell (x fastest): its colour map 1 position, or NaN for no data.
  std::vector<PLFLT> cell_color;
  std::vector<std::vector<PLFLT>> boundary_x, boundary_y;
  std::vector<std::vector<PLFLT>> curve_x, curve_y;  // the reference curves
  // Colour map 1's control points.
  std::vector<PLFLT> positions, red, green, blue;
  // The colour bar: its kind (PL_COLORBAR_GRADIENT or _SHADE (| _SHADE_LABEL)),
  // the values along it, its axis options and tick spacing (0: PLplot's).
  PLINT bar_kind = PL_COLORBAR_GRADIENT;
  bool z_boolean = false;
  std::vector<PLFLT> bar_values;
  std::string bar_axis;
  PLFLT bar_ticks = 0.0;
  PLFLT bar_gap = 0, bar_thickness = 0;  // normalised to the width
  std::string x_options, y_options;      // plbox's
  PLFLT x_ticks = 0.0, y_ticks = 0.0;
  PLINT x_subdivisions = 0, y_subdivisions = 0;
  PLFLT left = 0, right = 1, bottom = 0, top = 1;
  PLFLT x_label_offset = 0, y_label_offset = 0;
  std::string title, x_label, y_label, z_label;
  double title_font = 0.0;
};

PreparedMap prepare(const MapSpec& spec, double lo, double hi,
                    const std::vector<std::vector<Vec2>>& boundary) {
  const MapGrid& grid = spec.grid;
  PreparedMap map;
  map.width = spec.width;
  map.height = spec.height;
  map.metrics = ChartMetrics(spec.width, spec.height);
  const ChartMetrics& m = map.metrics;
  for (const double e : cell_edges(grid.x)) map.ex.push_back(e);
  for (const double e : cell_edges(grid.y)) map.ey.push_back(e);

  // Colours: false and true; bands between levels; or continuous.
  if (grid.z_boolean) {
    map.positions = {0.0, 1.0};
    map.red = {kFalseColor.r, kTrueColor.r};
    map.green = {kFalseColor.g, kTrueColor.g};
    map.blue = {kFalseColor.b, kTrueColor.b};
  } else {
    std::vector<double> samples;
    for (int k = 0; k < kColorPoints; ++k) samples.push_back(k / double(kColorPoints - 1));
    for (size_t k = 0; k < samples.size(); ++k) map.positions.push_back(samples[k]);
    for (const Rgb& color : map_colors(samples, 0.0, 1.0, spec.map)) {
      map.red.push_back(color.r);
      map.green.push_back(color.g);
      map.blue.push_back(color.b);
    }
  }
  const size_t bands = spec.levels.empty() ? 0 : spec.levels.size() - 1;
  for (const double z : grid.z) {
    if (std::isnan(z)) {
      map.cell_color.push_back(z);
    } else if (grid.z_boolean) {
      map.cell_color.push_back(z);
    } else if (bands > 0) {
      // Band b (between levels b and b + 1) as plshades colours it.
      const size_t b = std::min<size_t>(
          bands - 1, std::max<std::ptrdiff_t>(0, std::upper_bound(spec.levels.begin(),
                                                                  spec.levels.end(), z) -
                                                     spec.levels.begin() - 1));
      map.cell_color.push_back(static_cast<double>(b) / (bands - 1));
    } else {
      map.cell_color.push_back(std::clamp((z - lo) / (hi - lo), 0.0, 1.0));
    }
  }
  for (const std::vector<Vec2>& line : boundary) {
    map.boundary_x.emplace_back();
    map.boundary_y.emplace_back();
    for (const Vec2& p : line) {
      map.boundary_x.back().push_back(p.x());
      map.boundary_y.back().push_back(p.y());
    }
  }

  for (const std::vector<Vec2>& curve : spec.curves) {
    map.curve_x.emplace_back();
    map.curve_y.emplace_back();
    for (const Vec2& p : curve) {
      map.curve_x.back().push_back(p.x());
      map.curve_y.back().push_back(p.y());
    }
  }

  // The colour bar: false and true as two shades around ticks at 0 and 1.
  int bar_label_characters = 5;
  map.z_boolean = grid.z_boolean;
  if (grid.z_boolean) {
    map.bar_kind = PL_COLORBAR_SHADE;
    map.bar_values = {-0.5, 0.5, 1.5};
    map.bar_axis = "bcmtvo";
    map.bar_ticks = 1.0;
  } else if (bands > 0) {
    map.bar_kind = PL_COLORBAR_SHADE | PL_COLORBAR_SHADE_LABEL;
    map.bar_values.assign(spec.levels.begin(), spec.levels.end());
    map.bar_axis = "bcmtv";
    bar_label_characters = linear_label_characters(lo, hi) + 2;
  } else {
    map.bar_values = {lo, hi};
    map.bar_axis = "bcmtv";
    bar_label_characters = linear_label_characters(lo, hi);
  }
  // Axes of booleans: ticks at 0 and 1 only, labelled false and true.
  const auto box = [](bool boolean, const char* options, std::string& to, PLFLT& ticks,
                      PLINT& subdivisions) {
    to = std::string(options) + (boolean ? "o" : "");
    ticks = boolean ? 1.0 : 0.0;
    subdivisions = boolean ? 1 : 0;
  };
  box(grid.x_boolean, "bcnst", map.x_options, map.x_ticks, map.x_subdivisions);
  box(grid.y_boolean, "bcnstv", map.y_options, map.y_ticks, map.y_subdivisions);

  map.title = plplot_text(spec.title);
  map.title_font = std::min(1.2 * m.font, (spec.width - 2 * m.margin) /
                                              (kCharacterWidth * std::max<size_t>(1, spec.title.size())));
  map.x_label = plplot_text(spec.x_label);
  map.y_label = plplot_text(spec.y_label);
  map.z_label = plplot_text(spec.z_label);
  // Top to bottom: title, plot, x tick labels, x label.
  const double top = m.margin + (spec.title.empty() ? 0.6 * m.tick_font : 2.2 * m.font);
  const double x_labels = 2.6 * m.tick_font;
  const double bottom = m.margin + x_labels + (spec.x_label.empty() ? 0.0 : 1.6 * m.font);
  map.x_label_offset = (x_labels + 0.8 * m.font) / (kPlplotCharacterHeight * m.font);
  // Left to right: y label, y tick labels, plot, colour bar, its labels and label.
  const int y_characters =
      grid.y_boolean ? 5 : linear_label_characters(map.ey.front(), map.ey.back());
  const double y_labels = (kCharacterWidth * y_characters + 1.0) * m.tick_font;
  const double left = m.margin + y_labels + (spec.y_label.empty() ? 0.0 : 1.5 * m.font);
  map.y_label_offset = (y_labels + 0.6 * m.font) / (kPlplotCharacterHeight * m.font);
  const double gap = m.font, thickness = 1.2 * m.font;
  const double bar_labels = (kCharacterWidth * bar_label_characters + 1.0) * m.tick_font;
  const double z_band = spec.z_label.empty() ? 0.0 : 1.8 * m.font;
  map.bar_gap = gap / spec.width;
  map.bar_thickness = thickness / spec.width;
  map.top = 1.0 - top / spec.height;
  map.bottom = bottom / spec.height;
  map.left = left / spec.width;
  map.right = 1.0 - (m.margin + z_band + bar_labels + thickness + gap) / spec.width;
  if (map.right - map.left < 0.1 || map.top - map.bottom < 0.1) {
    throw InvalidArgument("chart: no room left for the map in " + std::to_string(spec.width) +
                          " x " + std::to_string(spec.height) +
                          "; make the image larger or the labels shorter");
  }
  return map;
}

// The map's PLplot calls (a PlplotPainter: plain values only).
void paint_map(void* context) {
  const PreparedMap& map = *static_cast<const PreparedMap*>(context);
  const ChartMetrics& m = map.metrics;
  plscmap0n(kColorCount);
  plplot_color(kBackground, {1.0, 1.0, 1.0});
  plplot_color(kText, kTextColor);
  plplot_color(kNoData, kNoDataColor);
  plplot_color(kBoundary, kBoundaryColor);
  plscmap1n(256);
  plscmap1l(1, static_cast<PLINT>(map.positions.size()), map.positions.data(), map.red.data(),
            map.green.data(), map.blue.data(), nullptr);
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  // Text in the text colour (plinit left colour 1 current, as it was then).
  plcol0(kText);
  plplot_page_title(map.title, map.title_font, m.margin + 0.7 * m.font);
  plvpor(map.left, map.right, map.bottom, map.top);
  plwind(map.ex.front(), map.ex.back(), map.ey.front(), map.ey.back());

  // Each row's runs of cells of one colour as one rectangle (a boolean map
  // of 40 x 40 cells is then a few dozen of them).
  const size_t nx = map.ex.size() - 1, ny = map.ey.size() - 1;
  const auto same = [](PLFLT a, PLFLT b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (size_t j = 0; j < ny; ++j) {
    for (size_t i = 0, end = 0; i < nx; i = end) {
      const PLFLT color = map.cell_color[j * nx + i];
      for (end = i + 1; end < nx && same(map.cell_color[j * nx + end], color);) ++end;
      if (std::isnan(color)) {
        plcol0(kNoData);
      } else {
        plcol1(color);
      }
      PLFLT x[] = {map.ex[i], map.ex[end], map.ex[end], map.ex[i]};
      PLFLT y[] = {map.ey[j], map.ey[j], map.ey[j + 1], map.ey[j + 1]};
      plfill(4, x, y);
    }
  }
  plcol0(kBoundary);
  plwidth(2.5 * m.line);
  for (size_t k = 0; k < map.boundary_x.size(); ++k) {
    plline(static_cast<PLINT>(map.boundary_x[k].size()), map.boundary_x[k].data(),
           map.boundary_y[k].data());
  }
  // Reference curves dashed (PLplot's style 3), so that they read apart
  // from the boundary where the two coincide.
  pllsty(3);
  for (size_t k = 0; k < map.curve_x.size(); ++k) {
    plline(static_cast<PLINT>(map.curve_x[k].size()), map.curve_x[k].data(), map.curve_y[k].data());
  }
  pllsty(1);

  plcol0(kText);
  plwidth(m.line);
  plplot_font(m.tick_font);
  plslabelfunc(plplot_boolean_label, nullptr);
  plbox(map.x_options.c_str(), map.x_ticks, map.x_subdivisions, map.y_options.c_str(),
        map.y_ticks, map.y_subdivisions);
  // The colour bar right of the plot, as tall as it, placed on the page
  // (from its top left corner).
  const char* axis[] = {map.bar_axis.c_str()};
  const PLFLT ticks[] = {map.bar_ticks};
  const PLINT sub_ticks[] = {map.z_boolean ? 1 : 0};
  const PLFLT* values[] = {map.bar_values.data()};
  const PLINT value_counts[] = {static_cast<PLINT>(map.bar_values.size())};
  const PLINT label_side[] = {PL_COLORBAR_LABEL_RIGHT};
  const char* labels[] = {map.z_label.c_str()};
  PLFLT bar_width = 0.0, bar_height = 0.0;
  plplot_font(m.tick_font);
  plcolorbar(&bar_width, &bar_height, map.bar_kind | PL_COLORBAR_ORIENT_TOP,
             PL_POSITION_SUBPAGE | PL_POSITION_INSIDE | PL_POSITION_LEFT | PL_POSITION_TOP,
             map.right + map.bar_gap, 1.0 - map.top, map.bar_thickness, map.top - map.bottom, 0,
             1, 1, 0.0, 0.0, 0,
             0.0, map.z_label.empty() ? 0 : 1, label_side, labels, 1, axis, ticks, sub_ticks,
             value_counts, values);
  plslabelfunc(nullptr, nullptr);
  plvpor(map.left, map.right, map.bottom, map.top);
  plwind(map.ex.front(), map.ex.back(), map.ey.front(), map.ey.back());
  plplot_font(m.font);
  if (!map.x_label.empty()) plmtex("b", map.x_label_offset, 0.5, 0.5, map.x_label.c_str());
  if (!map.y_label.empty()) plmtex("l", map.y_label_offset, 0.5, 0.5, map.y_label.c_str());
}

}  // namespace

std::vector<double> cell_edges(const std::vector<double>& values) {
  if (values.size() < 2) {
    throw InvalidArgument("chart: map: cells need at least 2 values along an axis, got " +
                          std::to_string(values.size()));
  }
  std::vector<double> edges{values[0] - (values[1] - values[0]) / 2};
  for (size_t k = 1; k < values.size(); ++k) edges.push_back((values[k - 1] + values[k]) / 2);
  const size_t n = values.size();
  edges.push_back(values[n - 1] + (values[n - 1] - values[n - 2]) / 2);
  return edges;
}

std::vector<std::vector<Vec2>> map_boundary(const MapSpec& spec) {
  if (spec.grid.z_boolean) return joined(boolean_boundary(spec.grid));
  if (spec.boundary) return joined(contour(spec.grid, *spec.boundary));
  return {};
}

MapDrawing draw_map(const std::string& path, const MapSpec& spec) {
  const ImageFormat format =
      image_format(path, {ImageFormat::png, ImageFormat::svg, ImageFormat::pdf}, "chart");
  check_map(spec);
  MapDrawing drawing;
  if (spec.grid.z_boolean) {
    drawing.lo = 0.0;
    drawing.hi = 1.0;
  } else if (!spec.levels.empty()) {
    drawing.lo = spec.levels.front();
    drawing.hi = spec.levels.back();
  } else {
    std::tie(drawing.lo, drawing.hi) = value_range(spec.grid.z);
    // Equal values: all 0 (the range then is 0 to 1), or one value < 0
    // (from it to 0).
    if (drawing.lo == drawing.hi) drawing.hi = drawing.lo < 0.0 ? 0.0 : 1.0;
  }
  drawing.boundary = map_boundary(spec);
  const PreparedMap map = prepare(spec, drawing.lo, drawing.hi, drawing.boundary);
  write_file_atomically(path, plplot_picture(format, spec.width, spec.height, paint_map,
                                             const_cast<PreparedMap*>(&map), "chart", path));
  drawing.frame.x.lo = map.ex.front();
  drawing.frame.x.hi = map.ex.back();
  drawing.frame.y.lo = map.ey.front();
  drawing.frame.y.hi = map.ey.back();
  drawing.frame.plot.left = map.left * spec.width;
  drawing.frame.plot.width = (map.right - map.left) * spec.width;
  drawing.frame.plot.top = (1.0 - map.top) * spec.height;
  drawing.frame.plot.height = (map.top - map.bottom) * spec.height;
  return drawing;
}

}  // namespace ashlar
