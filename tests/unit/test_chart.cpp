// Charts: the axes, and the files PLplot writes (pixels read back, the
// SVG's text, formats, threads, atomic writes); the rows of a study split
// into series.
#include <cairo.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <thread>

#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "io/chart.hpp"
#include "io/chart_map.hpp"
#include "io/chart_rows.hpp"
#include "io/color_map.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Two series crossing over x in [0, 2], y in [0, 4].
ChartSpec crossing_series(ChartKind kind = ChartKind::points) {
  ChartSpec spec;
  spec.series = {{"rising", {{0, 0}, {1, 1}, {2, 4}}}, {"falling", {{0, 4}, {1, 3}, {2, 0}}}};
  spec.kind = kind;
  spec.title = "two series";
  spec.x_label = "x";
  spec.y_label = "y";
  return spec;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* surface) const { cairo_surface_destroy(surface); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;

Surface read_png(const std::string& path) {
  Surface surface(cairo_image_surface_create_from_png(path.c_str()));
  EXPECT_EQ(cairo_surface_status(surface.get()), CAIRO_STATUS_SUCCESS) << path;
  return surface;
}

// 8-bit red, green and blue of the pixel that holds image point p.
std::array<int, 3> pixel(cairo_surface_t* surface, const Vec2& p) {
  cairo_surface_flush(surface);
  const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
  const unsigned char* row =
      cairo_image_surface_get_data(surface) + y * cairo_image_surface_get_stride(surface);
  // Native-endian 0xAARRGGBB (or xRGB), opaque here so not premultiplied.
  const uint32_t argb = reinterpret_cast<const uint32_t*>(row)[x];
  return {int((argb >> 16) & 0xff), int((argb >> 8) & 0xff), int(argb & 0xff)};
}

std::array<int, 3> eight_bit(const Rgb& color) {
  return {int(std::lround(color.r * 255)), int(std::lround(color.g * 255)),
          int(std::lround(color.b * 255))};
}

// The smallest difference (largest over channels) between `color` and the
// pixels around image point p (3 x 3): thin lines cover a pixel fully only
// near their middle.
int color_distance_near(cairo_surface_t* surface, const Vec2& p, const std::array<int, 3>& color) {
  int closest = 255;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      const std::array<int, 3> found = pixel(surface, p + Vec2(dx, dy));
      int distance = 0;
      for (int c = 0; c < 3; ++c) distance = std::max(distance, std::abs(found[c] - color[c]));
      closest = std::min(closest, distance);
    }
  }
  return closest;
}

void expect_color(const std::array<int, 3>& actual, const std::array<int, 3>& expected,
                  const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(actual[c], expected[c], 2) << what << ", channel " << c;
  }
}

}  // namespace

TEST(ChartAxes, PadTheData) {
  const ChartSpec spec = crossing_series();
  const auto [x, y] = chart_axes(spec);
  // 4 % of the data's range on each side.
  EXPECT_DOUBLE_EQ(x.lo, -0.08);
  EXPECT_DOUBLE_EQ(x.hi, 2.08);
  EXPECT_DOUBLE_EQ(y.lo, -0.16);
  EXPECT_DOUBLE_EQ(y.hi, 4.16);
  EXPECT_DOUBLE_EQ(x.fraction(1.0), 0.5);

  // Log axes: padded by 4 % of 3 decades, 0.12 decades.
  ChartSpec log;
  log.series = {{"error", {{1, 1e-6}, {10, 1e-4}, {100, 1e-2}, {1000, 1}}}};
  log.log_x = log.log_y = true;
  const auto [log_x, log_y] = chart_axes(log);
  EXPECT_NEAR(std::log10(log_x.lo), -0.12, 1e-12);
  EXPECT_NEAR(std::log10(log_y.hi), 0.24, 1e-12);
  EXPECT_NEAR(log_x.fraction(10) - log_x.fraction(1), log_x.fraction(1000) - log_x.fraction(100),
              1e-12);

  // A single value gets a range: ± 5 % of it, ± 0.5 for 0.
  ChartSpec single;
  single.series = {{"one", {{0.08, 0}}}};
  const auto [single_x, single_y] = chart_axes(single);
  EXPECT_DOUBLE_EQ(single_x.lo, 0.076);
  EXPECT_DOUBLE_EQ(single_x.hi, 0.084);
  EXPECT_DOUBLE_EQ(single_y.lo, -0.5);
  EXPECT_DOUBLE_EQ(single_y.hi, 0.5);
}

TEST(ChartAxes, TakeTheGivenRanges) {
  ChartSpec spec = crossing_series();
  spec.x_range = std::make_pair(0.5, 1.5);
  spec.y_range = std::make_pair(-8.0, 2.0);
  const auto [x, y] = chart_axes(spec);
  EXPECT_EQ(x.lo, 0.5);
  EXPECT_EQ(x.hi, 1.5);
  EXPECT_EQ(y.lo, -8.0);
  EXPECT_EQ(y.hi, 2.0);
  spec.log_y = true;
  spec.series = {{"positive", {{1, 1}}}};
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }),
                       "chart: y_range must be finite with lo < hi and lo > 0 (log axis), got {-8, 2}"));
  spec.log_y = false;
  spec.x_range = std::make_pair(1.0, 1.0);
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }),
                       "chart: x_range must be finite with lo < hi, got {1, 1}"));
}

TEST(ChartAxes, RejectBadSpecs) {
  ChartSpec spec = crossing_series();
  spec.width = 199;
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }),
                       "width and height must lie in [200, 16384], got 199 x 600"));
  spec = crossing_series();
  spec.log_y = true;
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }),
                       "log_y takes values > 0 only, got series 'rising' point 1 (x = 0, y = 0)"));
  spec = crossing_series();
  spec.series[1].points[2].y() = INFINITY;
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }),
                       "series 'falling' point 3 (x = 2, y = inf) is not finite"));
  spec.series = {{"empty", {}}};
  EXPECT_TRUE(contains(error_of([&] { chart_axes(spec); }), "nothing to plot"));
  EXPECT_TRUE(contains(error_of([] { chart_kind("bars"); }),
                       "unknown kind 'bars' (allowed: lines, points, linespoints, steps, map)"));
}

TEST(Chart, PngShowsEachSeriesInItsColourAtItsPoints) {
  TempDir dir;
  const ChartSpec spec = crossing_series(ChartKind::linespoints);
  const ChartFrame frame = draw_chart(dir.file("c.png"), spec);
  const Surface image = read_png(dir.file("c.png"));
  EXPECT_EQ(cairo_image_surface_get_width(image.get()), 900);
  EXPECT_EQ(cairo_image_surface_get_height(image.get()), 600);
  // The frame lies inside the image, the legend's room on its right.
  EXPECT_GT(frame.plot.left, 0);
  EXPECT_GT(frame.plot.top, 0);
  EXPECT_LT(frame.plot.right(), 0.88 * spec.width);
  EXPECT_LT(frame.plot.bottom(), spec.height);
  const std::array<int, 3> blue = eight_bit(chart_series_color(0));
  const std::array<int, 3> vermillion = eight_bit(chart_series_color(1));
  EXPECT_EQ(blue, (std::array<int, 3>{0, 114, 178}));
  EXPECT_EQ(vermillion, (std::array<int, 3>{213, 94, 0}));
  // The markers sit on the data points in their series' colours (PLplot
  // rounds positions to whole pixels: 3 x 3 around each).
  EXPECT_LE(color_distance_near(image.get(), frame.to_image({2, 4}), blue), 2);
  EXPECT_LE(color_distance_near(image.get(), frame.to_image({1, 1}), blue), 2);
  EXPECT_LE(color_distance_near(image.get(), frame.to_image({2, 0}), vermillion), 2);
  EXPECT_LE(color_distance_near(image.get(), frame.to_image({1, 3}), vermillion), 2);
  // Where no series goes: white or a light grid line.
  const std::array<int, 3> empty = pixel(image.get(), frame.to_image({0.3, 2.2}));
  for (const int channel : empty) EXPECT_GE(channel, 200);
  // The image corner is background.
  expect_color(pixel(image.get(), {1, 1}), {255, 255, 255}, "corner");

  // Steps: the value 1 holds from x = 1 to x = 2, then jumps to 4; a line
  // would run diagonally through (1.5, 2.5) instead.
  const ChartSpec steps = crossing_series(ChartKind::steps);
  const ChartFrame steps_frame = draw_chart(dir.file("steps.png"), steps);
  const Surface steps_image = read_png(dir.file("steps.png"));
  EXPECT_LE(color_distance_near(steps_image.get(), steps_frame.to_image({1.5, 1}), blue), 2);
  EXPECT_GE(color_distance_near(steps_image.get(), steps_frame.to_image({1.5, 2.5}), blue), 100);

  // One series: no legend, the plot reaches nearly to the image's edge.
  ChartSpec single = crossing_series();
  single.series.pop_back();
  EXPECT_GT(draw_chart(dir.file("single.png"), single).plot.right(), 0.9 * single.width);

  // Another size: the image follows.
  ChartSpec small = crossing_series();
  small.width = 400;
  small.height = 300;
  draw_chart(dir.file("small.png"), small);
  const Surface small_image = read_png(dir.file("small.png"));
  EXPECT_EQ(cairo_image_surface_get_width(small_image.get()), 400);
  EXPECT_EQ(cairo_image_surface_get_height(small_image.get()), 300);
}

TEST(Chart, WritesSvgWithItsTextAndPdf) {
  TempDir dir;
  ChartSpec spec = crossing_series();
  spec.series[1].name = "falling #2 <&>";  // PLplot's escape and XML's specials
  draw_chart(dir.file("c.svg"), spec);
  const std::string svg = read_file(dir.file("c.svg"));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_TRUE(contains(svg, "width=\"900pt\"\n  height=\"600pt\"")) << svg.substr(0, 400);
  EXPECT_TRUE(contains(svg, "</svg>"));
  // Title, axis labels, legend entries and tick labels are text.
  const std::vector<std::string> texts = svg_texts(svg);
  for (const std::string text : {"two series", "x", "y", "rising", "falling #2 <&>", "0.5", "4"}) {
    EXPECT_TRUE(has_text(texts, text)) << text;
  }
  draw_chart(dir.file("c.PDF"), spec);
  const std::string pdf = read_file(dir.file("c.PDF"));
  EXPECT_EQ(pdf.rfind("%PDF", 0), 0u);
  EXPECT_TRUE(contains(pdf, "%%EOF"));
  EXPECT_TRUE(contains(pdf, "/MediaBox [ 0 0 900 600 ]"));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"c.PDF", "c.svg"}));
}

TEST(Chart, LogAxesLabelTheirDecades) {
  TempDir dir;
  ChartSpec spec;
  spec.series = {{"error", {{1, 1e-6}, {10, 1e-4}, {100, 1e-2}, {1000, 1}}}};
  spec.log_x = spec.log_y = true;
  draw_chart(dir.file("log.svg"), spec);
  const std::vector<std::string> texts = svg_texts(read_file(dir.file("log.svg")));
  // x from 10^-0.12 to 10^3.12, y from 10^-6.24 to 10^0.24: every decade.
  for (const std::string label : {"10^0", "10^1", "10^2", "10^3"}) {
    EXPECT_TRUE(has_text(texts, label)) << label;
  }
  for (int exponent = -6; exponent <= 0; ++exponent) {
    EXPECT_TRUE(has_text(texts, "10^" + std::to_string(exponent))) << exponent;
  }
  EXPECT_FALSE(has_text(texts, "10^4"));
  EXPECT_FALSE(has_text(texts, "10^-7"));
}

// Small and large values are written over a power of ten that the y
// label states, inside the picture (PLplot put its own above the axis,
// where the title is, and the page cut it off).
TEST(Chart, SmallAndLargeValuesAreWrittenOverAPowerOfTenTheLabelStates) {
  TempDir dir;
  ChartSpec spec;
  spec.title = "title";
  spec.y_label = "displacement (m)";
  spec.series = {{"slid", {{0, 0}, {1, 2.1e-4}, {2, 6.6e-4}}}};
  draw_chart(dir.file("small.svg"), spec);
  std::vector<std::string> texts = svg_texts(read_file(dir.file("small.svg")));
  for (const std::string label : {"displacement (m), ×10^-4", "0", "2", "4", "6"}) {
    EXPECT_TRUE(has_text(texts, label)) << label;
  }
  EXPECT_FALSE(has_text(texts, "0.0002"));
  spec.series = {{"force", {{0, -2e5}, {1, 3e5}}}};
  draw_chart(dir.file("large.svg"), spec);
  texts = svg_texts(read_file(dir.file("large.svg")));
  for (const std::string label : {"displacement (m), ×10^5", "-2", "0", "2"}) {
    EXPECT_TRUE(has_text(texts, label)) << label;
  }
  // Between 0.01 and 1e5 values are written as they are.
  spec.series = {{"ratio", {{0, 0}, {1, 0.05}}}};
  draw_chart(dir.file("plain.svg"), spec);
  texts = svg_texts(read_file(dir.file("plain.svg")));
  EXPECT_TRUE(has_text(texts, "displacement (m)"));
  EXPECT_TRUE(has_text(texts, "0.01")) << ::testing::PrintToString(texts);
}

TEST(Chart, ManyThreadsDrawAtOnce) {
  TempDir dir;
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (int i = 0; i < 3; ++i) draw_chart(dir.file(std::to_string(k * 3 + i) + ".png"), crossing_series());
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(dir.entries().size(), 12u);
  for (const std::string& name : dir.entries()) {
    EXPECT_EQ(read_file(dir.file(name)).rfind("\x89PNG", 0), 0u) << name;
  }
}

TEST(Chart, WritesAtomically) {
  TempDir dir;
  const ChartSpec spec = crossing_series();
  const std::string path = dir.file("c.png");
  write_file_atomically(path, "old");
  EXPECT_TRUE(contains(error_of([&] { draw_chart(dir.file("c.jpg"), spec); }),
                       "chart: cannot tell the format of"));
  EXPECT_TRUE(
      contains(error_of([&] { draw_chart(dir.file("c.jpg"), spec); }), "use .png, .svg or .pdf"));
  ChartSpec bad = spec;
  bad.log_y = true;
  EXPECT_TRUE(contains(error_of([&] { draw_chart(path, bad); }), "log_y"));
  EXPECT_EQ(read_file(path), "old");

  // A write that succeeds replaces it, with no temporary left.
  draw_chart(path, spec);
  EXPECT_EQ(read_file(path).rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"c.png"}));

  // A write that fails part-way (the file size limit is far below a PNG's
  // size) leaves the old file and no temporary. (PLplot has read its list
  // of drivers above: it writes a temporary file to do so, once.)
  write_file_atomically(path, "old");
  struct rlimit saved;
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = signal(SIGXFSZ, SIG_IGN);  // write() fails with EFBIG instead
  struct rlimit tiny = saved;
  tiny.rlim_cur = 64;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &tiny), 0);
  const std::string error = error_of([&] { draw_chart(path, spec); });
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, old_handler);
  EXPECT_TRUE(contains(error, "cannot write '" + path + "'")) << error;
  EXPECT_EQ(read_file(path), "old");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"c.png"}));
}

TEST(ChartRows, SplitsRowsIntoSortedSeries) {
  const auto number = [](double v) { return ChartCell{ChartCell::Type::number, v, ""}; };
  const auto boolean = [](bool v) {
    return ChartCell{ChartCell::Type::boolean, v ? 1.0 : 0.0, ""};
  };
  const auto text = [](const std::string& v) { return ChartCell{ChartCell::Type::text, 0, v}; };
  const std::vector<ChartRow> rows = {
      {{"t", number(0.2)}, {"n", number(16)}, {"inf", number(0.0)}, {"stable", boolean(true)}},
      {{"t", number(0.1)}, {"n", number(16)}, {"inf", number(0.3)}, {"stable", boolean(false)}},
      {{"t", number(0.1)}, {"n", number(8)}, {"inf", number(0.5)}, {"stable", boolean(false)}},
      {{"t", number(0.15)}, {"n", number(8)}, {"status", text("failed")}},
      {{"t", number(0.2)}, {"n", text("many")}, {"inf", number(0.1)}, {"stable", boolean(true)}},
      {{"t", number(0.3)}, {"inf", number(0.0)}, {"stable", boolean(true)}},
  };
  RowSeries lines = series_from_rows(rows, {"t", {"inf"}, {"n"}});
  ASSERT_EQ(lines.series.size(), 4u);
  EXPECT_EQ(lines.series[0].name, "n = 8");  // 8 before 16: numeric order
  EXPECT_EQ(lines.series[1].name, "n = 16");
  EXPECT_EQ(lines.series[2].name, "n = many");
  EXPECT_EQ(lines.series[3].name, "n = nil");
  EXPECT_EQ(lines.series[1].points, (std::vector<Vec2>{{0.1, 0.3}, {0.2, 0.0}}));  // sorted by x
  EXPECT_EQ(lines.skipped, 1);  // the failed run has no inf

  // Two y columns, booleans as 0 and 1, no series column.
  lines = series_from_rows(rows, {"t", {"inf", "stable"}, {}});
  ASSERT_EQ(lines.series.size(), 2u);
  EXPECT_EQ(lines.series[1].name, "stable");
  EXPECT_EQ(lines.series[1].points,
            (std::vector<Vec2>{{0.1, 0}, {0.1, 0}, {0.2, 1}, {0.2, 1}, {0.3, 1}}));
  lines = series_from_rows(rows, {"t", {"inf", "stable"}, {"n"}});
  EXPECT_EQ(lines.series[0].name, "inf, n = 8");

  // Strings in natural order; leading zeros keep values apart.
  std::vector<ChartRow> named;
  for (const std::string name : {"case 10", "case 2", "case 02", "case 1b", "case 1a", "Case"}) {
    named.push_back({{"t", number(1)}, {"y", number(2)}, {"name", text(name)}});
  }
  std::vector<std::string> names;
  for (const ChartSeries& line : series_from_rows(named, {"t", {"y"}, {"name"}}).series) {
    names.push_back(line.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"name = Case", "name = case 1a", "name = case 1b",
                                             "name = case 02", "name = case 2", "name = case 10"}));

  EXPECT_TRUE(contains(error_of([&] {
                         series_from_rows(rows, {"tt", {"inf"}, {}});
                       }),
                       "chart: x: no row has a column 'tt' (columns: inf, n, stable, status, t)"));
  EXPECT_TRUE(contains(error_of([&] {
                         series_from_rows(rows, {"t", {"status"}, {}});
                       }),
                       "chart: y: row 4 has a string (\"failed\") in column 'status'"));
  EXPECT_TRUE(contains(error_of([&] {
                         series_from_rows(rows, {"t", {"inf", "inf"}, {}});
                       }),
                       "y: column 'inf' is listed twice"));
  const std::vector<ChartRow> disjoint = {{{"t", number(0.1)}}, {{"inf", number(0.3)}}};
  EXPECT_TRUE(contains(error_of([&] {
                         series_from_rows(disjoint, {"t", {"inf"}, {}});
                       }),
                       "chart: nothing to plot: no row has both x ('t') and y ('inf'); 2 rows "
                       "skipped"));
  // A point whose value is not finite is skipped and counted, as a
  // missing one (a study's math.huge friction, an analysis without answer).
  std::vector<ChartRow> not_finite = rows;
  not_finite[2]["inf"] = number(NAN);
  const RowSeries all = series_from_rows(rows, {"t", {"inf"}, {}});
  const RowSeries kept = series_from_rows(not_finite, {"t", {"inf"}, {}});
  EXPECT_EQ(kept.skipped, all.skipped + 1);
  EXPECT_EQ(kept.series.at(0).points.size(), all.series.at(0).points.size() - 1);
  EXPECT_TRUE(contains(error_of([&] {
                         series_from_rows({}, {"t", {"inf"}, {}});
                       }),
                       "chart: nothing to plot: data has no rows"));
}

TEST(ChartMap, CellsSitAtTheirGridPointsInTheirColours) {
  // z = stable over x in {3, 1, 2} (unsorted rows) × y in {10, 20}; the
  // row at (3, 20) has no z: no data.
  const auto number = [](double v) { return ChartCell{ChartCell::Type::number, v, ""}; };
  const auto boolean = [](bool v) {
    return ChartCell{ChartCell::Type::boolean, v ? 1.0 : 0.0, ""};
  };
  std::vector<ChartRow> rows;
  for (const double y : {20.0, 10.0}) {
    for (const double x : {3.0, 1.0, 2.0}) {
      ChartRow row{{"x", number(x)}, {"y", number(y)}};
      if (!(x == 3 && y == 20)) row["z"] = boolean(x >= 2 && y >= 20);
      rows.push_back(row);
    }
  }
  MapSpec spec;
  spec.grid = grid_from_rows(rows, "x", "y", "z");
  EXPECT_EQ(spec.grid.x, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(spec.grid.y, (std::vector<double>{10, 20}));
  EXPECT_TRUE(spec.grid.z_boolean);
  EXPECT_EQ(spec.grid.no_data, 1);
  TempDir dir;
  const MapDrawing drawing = draw_map(dir.file("m.png"), spec);
  EXPECT_DOUBLE_EQ(drawing.frame.x.lo, 0.5);
  EXPECT_DOUBLE_EQ(drawing.frame.x.hi, 3.5);
  EXPECT_DOUBLE_EQ(drawing.frame.y.lo, 5);
  EXPECT_DOUBLE_EQ(drawing.frame.y.hi, 25);
  // The boundary: left of and under the one true cell (2, 20); none
  // between it and the cell without data.
  ASSERT_EQ(drawing.boundary.size(), 1u);
  EXPECT_EQ(drawing.boundary[0],
            (std::vector<Vec2>{{1.5, 25}, {1.5, 15}, {2.5, 15}}));
  const Surface image = read_png(dir.file("m.png"));
  // Vermillion and blue halfway to white; no data light grey.
  const std::array<int, 3> false_color{234, 175, 128}, true_color{128, 185, 217},
      no_data{217, 217, 217};
  expect_color(pixel(image.get(), drawing.frame.to_image({1, 10})), false_color, "(1, 10)");
  expect_color(pixel(image.get(), drawing.frame.to_image({3, 10})), false_color, "(3, 10)");
  expect_color(pixel(image.get(), drawing.frame.to_image({1.2, 22})), false_color, "(1, 20)");
  expect_color(pixel(image.get(), drawing.frame.to_image({2.2, 22})), true_color, "(2, 20)");
  expect_color(pixel(image.get(), drawing.frame.to_image({3.2, 22})), no_data, "(3, 20)");
}

TEST(ChartMap, RefusesRowsThatDoNotFormAGrid) {
  const auto number = [](double v) { return ChartCell{ChartCell::Type::number, v, ""}; };
  std::vector<ChartRow> rows = {{{"a", number(1)}, {"b", number(1)}, {"z", number(0)}},
                                {{"a", number(2)}, {"b", number(1)}, {"z", number(0)}},
                                {{"a", number(2)}, {"b", number(3)}, {"z", number(0)}}};
  EXPECT_TRUE(contains(error_of([&] { grid_from_rows(rows, "a", "b", "z"); }),
                       "no row at (a = 1, b = 3) (2 a values × 2 b values, 3 rows)"));
  rows.push_back({{"a", number(2)}, {"b", number(3)}, {"z", number(1)}});
  EXPECT_TRUE(contains(error_of([&] { grid_from_rows(rows, "a", "b", "z"); }),
                       "rows 3 and 4 are both at (a = 2, b = 3)"));
  rows.pop_back();
  rows.push_back({{"a", number(1)}, {"z", number(1)}});
  EXPECT_TRUE(contains(error_of([&] { grid_from_rows(rows, "a", "b", "z"); }),
                       "row 4 has no finite b (nil)"));
}

TEST(ColorMap, ValueRangesOfNonNegativeValuesStartAtZero) {
  EXPECT_EQ(value_range({3.337e-11, 3591.0, 12.0}), (std::pair<double, double>{0.0, 3591.0}));
  EXPECT_EQ(value_range({-2.0, 5.0}), (std::pair<double, double>{-2.0, 5.0}));
  EXPECT_EQ(value_range({-2.0, -1.0}), (std::pair<double, double>{-2.0, -1.0}));
  EXPECT_EQ(value_range({std::nan(""), 4.0, INFINITY}), (std::pair<double, double>{0.0, 4.0}));
  EXPECT_EQ(value_range({}), (std::pair<double, double>{0.0, 0.0}));
}
