// Charts: axis ticks, the layout, and the files (pixels read back, formats,
// atomic writes).
#include <cairo.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "io/axis_ticks.hpp"
#include "io/chart.hpp"
#include "io/chart_rows.hpp"
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

TEST(AxisTicks, LinearStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  AxisTicks ticks = linear_ticks(0, 1, 6);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_TRUE(ticks.minor.empty());
  // One more allowed tick: the step drops to 0.1.
  EXPECT_EQ(linear_ticks(0, 1, 11).values.size(), 11u);
  // Ends off the step: only multiples inside, with the step's decimals.
  ticks = linear_ticks(0.073, 0.207, 8);
  EXPECT_EQ(ticks.values, (std::vector<double>{0.08, 0.1, 0.12, 0.14, 0.16, 0.18, 0.2}));
  EXPECT_EQ(ticks.labels,
            (std::vector<std::string>{"0.08", "0.10", "0.12", "0.14", "0.16", "0.18", "0.20"}));
  // Negative values with a true minus sign; step 2 gives 8 ticks, step 1 would give 16.
  ticks = linear_ticks(-3.7, 12.2, 8);
  EXPECT_EQ(ticks.values, (std::vector<double>{-2, 0, 2, 4, 6, 8, 10, 12}));
  EXPECT_EQ(ticks.labels.front(), "\u22122");
  // At most 6: step 5 (step 2 would give 8).
  EXPECT_EQ(linear_ticks(-3.7, 12.2, 6).values, (std::vector<double>{0, 5, 10}));
  // Round-off: 0.3 / 0.1 is 2.9999999999999996, and 0.3 is still a tick.
  EXPECT_EQ(linear_ticks(0.1, 0.3, 3).values, (std::vector<double>{0.1, 0.2, 0.3}));
}

TEST(AxisTicks, LinearLabelsOfLargeAndSmallValuesShareAPowerOfTen) {
  AxisTicks ticks = linear_ticks(0, 3.2e7, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 1e7, 2e7, 3e7}));
  EXPECT_EQ(ticks.power, 7);
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"0", "1", "2", "3"}));
  ticks = linear_ticks(-5.2e6, 1.52e7, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{-5e6, 0, 5e6, 1e7, 1.5e7}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"\u22120.5", "0.0", "0.5", "1.0", "1.5"}));
  // One more allowed: step 2×10⁶ from 1.2×10⁷; one fewer: step 5×10⁶.
  ticks = linear_ticks(1.2e7, 2.1e7, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{1.2e7, 1.4e7, 1.6e7, 1.8e7, 2e7}));
  EXPECT_EQ(ticks.labels[4], "2.0");
  EXPECT_EQ(linear_ticks(1.2e7, 2.1e7, 4).values, (std::vector<double>{1.5e7, 2e7}));
  ticks = linear_ticks(0, 3e-5, 4);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 1e-5, 2e-5, 3e-5}));
  EXPECT_EQ(ticks.power, -5);
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"0", "1", "2", "3"}));
  // Just under a million: plain.
  ticks = linear_ticks(0, 9e5, 10);
  EXPECT_EQ(ticks.power, 0);
  EXPECT_EQ(ticks.labels.back(), "900000");
  EXPECT_EQ(linear_label_power(-2e6, 1), 6);
  EXPECT_EQ(linear_label_power(0, 9.9e-5), -5);
  EXPECT_EQ(linear_label_power(0, 0.5), 0);
  EXPECT_EQ(power_of_ten_text(-12), "10\u207b\u00b9\u00b2");
}

TEST(AxisTicks, LogAxesUseDecadesThenOneTwoFive) {
  AxisTicks ticks = log_ticks(1e-3, 10, 6);
  EXPECT_EQ(ticks.values, (std::vector<double>{1e-3, 1e-2, 0.1, 1, 10}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"0.001", "0.01", "0.1", "1", "10"}));
  // 2..9 in each of the four decades.
  ASSERT_EQ(ticks.minor.size(), 32u);
  EXPECT_DOUBLE_EQ(ticks.minor.front(), 2e-3);
  EXPECT_DOUBLE_EQ(ticks.minor.back(), 9);

  // Thirteen decades, at most 6 ticks: every fifth decade (every second gives 7).
  ticks = log_ticks(1e-12, 1, 6);
  EXPECT_EQ(ticks.values, (std::vector<double>{1e-10, 1e-5, 1}));
  EXPECT_EQ(ticks.labels,
            (std::vector<std::string>{"10\u207b\u00b9\u2070", "10\u207b\u2075", "10\u2070"}));
  EXPECT_TRUE(ticks.minor.empty());

  // About a decade: 1, 2 and 5 times powers of ten.
  ticks = log_ticks(3, 40, 6);
  EXPECT_EQ(ticks.values, (std::vector<double>{5, 10, 20}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"5", "10", "20"}));
  ticks = log_ticks(0.015, 0.3, 6);
  EXPECT_EQ(ticks.values, (std::vector<double>{0.02, 0.05, 0.1, 0.2}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"0.02", "0.05", "0.1", "0.2"}));

  // 1, 2, 5, 10 is one too many for 3: the two decades, with minor ticks
  // (0.9 is one: it lies inside).
  ticks = log_ticks(0.9, 11, 3);
  EXPECT_EQ(ticks.values, (std::vector<double>{1, 10}));
  EXPECT_EQ(ticks.minor, (std::vector<double>{0.9, 2, 3, 4, 5, 6, 7, 8, 9}));

  // Under a decade with no 1, 2 or 5 inside: linear ticks.
  ticks = log_ticks(1.2, 1.8, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{1.2, 1.4, 1.6, 1.8}));
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"1.2", "1.4", "1.6", "1.8"}));
}

TEST(AxisTicks, RejectBadRanges) {
  EXPECT_TRUE(contains(error_of([] { linear_ticks(1, 1, 5); }), "lo < hi"));
  EXPECT_TRUE(contains(error_of([] { linear_ticks(0, NAN, 5); }), "finite"));
  EXPECT_TRUE(contains(error_of([] { linear_ticks(0, 1, 1); }), "at least 2 ticks"));
  EXPECT_TRUE(contains(error_of([] { log_ticks(0, 1, 5); }), "0 < lo < hi"));
}

TEST(ChartLayout, PadsTheDataAndMapsItInsideThePlot) {
  const ChartSpec spec = crossing_series();
  const ChartLayout layout = chart_layout(spec);
  // 4 % of the data's range on each side.
  EXPECT_DOUBLE_EQ(layout.x.lo, -0.08);
  EXPECT_DOUBLE_EQ(layout.x.hi, 2.08);
  EXPECT_DOUBLE_EQ(layout.y.lo, -0.16);
  EXPECT_DOUBLE_EQ(layout.y.hi, 4.16);
  // The axes' ends are the plot's edges.
  EXPECT_TRUE(
      layout.to_image({-0.08, -0.16}).isApprox(Vec2(layout.plot.left, layout.plot.bottom())));
  EXPECT_TRUE(layout.to_image({2.08, 4.16}).isApprox(Vec2(layout.plot.right(), layout.plot.top)));
  // Every point strictly inside, and inside the image.
  for (const ChartSeries& series : spec.series) {
    for (const Vec2& p : series.points) {
      const Vec2 q = layout.to_image(p);
      EXPECT_GT(q.x(), layout.plot.left + 5);
      EXPECT_LT(q.x(), layout.plot.right() - 5);
      EXPECT_GT(q.y(), layout.plot.top + 5);
      EXPECT_LT(q.y(), layout.plot.bottom() - 5);
    }
  }
  EXPECT_GT(layout.plot.left, 0);
  EXPECT_GT(layout.plot.top, 0);
  // The legend sits right of the plot, inside the image.
  EXPECT_GT(layout.legend.width, 0);
  EXPECT_GT(layout.legend.left, layout.plot.right());
  EXPECT_LE(layout.legend.right(), spec.width);
  // Ticks: 1-2-5 steps inside the axis, labelled.
  // About one per five label heights, at most 10: step 0.2 would give 11.
  EXPECT_EQ(layout.x.ticks.values, (std::vector<double>{0, 0.5, 1, 1.5, 2}));
  EXPECT_EQ(layout.y.ticks.values, (std::vector<double>{0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4}));
  EXPECT_EQ(layout.y.ticks.labels.size(), layout.y.ticks.values.size());

  // One series: no legend, the plot reaches to the margin.
  ChartSpec single = spec;
  single.series.pop_back();
  const ChartLayout alone = chart_layout(single);
  EXPECT_EQ(alone.legend.width, 0);
  EXPECT_GT(alone.plot.width, layout.plot.width + layout.legend.width);
}

TEST(ChartLayout, LogAxesSpaceDecadesEvenly) {
  ChartSpec spec;
  spec.series = {{"error", {{1, 1e-6}, {10, 1e-4}, {100, 1e-2}, {1000, 1}}}};
  spec.log_x = spec.log_y = true;
  const ChartLayout layout = chart_layout(spec);
  // Padded by 4 % of 3 decades: 0.12 decades.
  EXPECT_NEAR(std::log10(layout.x.lo), -0.12, 1e-12);
  EXPECT_NEAR(std::log10(layout.y.hi), 0.24, 1e-12);
  const double decade = layout.to_image({10, 1}).x() - layout.to_image({1, 1}).x();
  EXPECT_NEAR(layout.to_image({1000, 1}).x() - layout.to_image({100, 1}).x(), decade, 1e-9);
  EXPECT_NEAR(layout.to_image({1, 1e-4}).y() - layout.to_image({1, 1e-6}).y(),
              layout.to_image({1, 1}).y() - layout.to_image({1, 1e-2}).y(), 1e-9);
  EXPECT_EQ(layout.x.ticks.values, (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_EQ(layout.y.ticks.labels.front(), "10\u207b\u2076");
}

TEST(ChartLayout, SingleValuesGetARange) {
  ChartSpec spec;
  spec.series = {{"one", {{0.08, 0}}}};
  const ChartLayout layout = chart_layout(spec);
  EXPECT_DOUBLE_EQ(layout.x.lo, 0.076);
  EXPECT_DOUBLE_EQ(layout.x.hi, 0.084);
  EXPECT_DOUBLE_EQ(layout.y.lo, -0.5);
  EXPECT_DOUBLE_EQ(layout.y.hi, 0.5);
  EXPECT_GE(layout.x.ticks.values.size(), 2u);
}

TEST(ChartLayout, RejectsBadSpecs) {
  ChartSpec spec = crossing_series();
  spec.width = 199;
  EXPECT_TRUE(contains(error_of([&] { chart_layout(spec); }),
                       "width and height must lie in [200, 16384], got 199 x 600"));
  spec = crossing_series();
  spec.log_y = true;
  EXPECT_TRUE(contains(error_of([&] { chart_layout(spec); }),
                       "log_y takes values > 0 only, got series 'rising' point 1 (x = 0, y = 0)"));
  spec = crossing_series();
  spec.series[1].points[2].y() = INFINITY;
  EXPECT_TRUE(contains(error_of([&] { chart_layout(spec); }),
                       "series 'falling' point 3 (x = 2, y = inf) is not finite"));
  spec.series = {{"empty", {}}};
  EXPECT_TRUE(contains(error_of([&] { chart_layout(spec); }), "nothing to plot"));
  EXPECT_TRUE(contains(error_of([] { chart_kind("bars"); }),
                       "unknown kind 'bars' (allowed: lines, points, linespoints, steps)"));
}

TEST(Chart, PngShowsEachSeriesInItsColourAtItsPoints) {
  TempDir dir;
  const ChartSpec spec = crossing_series(ChartKind::linespoints);
  const ChartLayout layout = chart_layout(spec);
  draw_chart(dir.file("c.png"), spec);
  const Surface image = read_png(dir.file("c.png"));
  EXPECT_EQ(cairo_image_surface_get_width(image.get()), 900);
  EXPECT_EQ(cairo_image_surface_get_height(image.get()), 600);
  const std::array<int, 3> blue = eight_bit(chart_series_color(0));
  const std::array<int, 3> vermillion = eight_bit(chart_series_color(1));
  EXPECT_EQ(blue, (std::array<int, 3>{0, 114, 178}));
  EXPECT_EQ(vermillion, (std::array<int, 3>{213, 94, 0}));
  expect_color(pixel(image.get(), layout.to_image({2, 4})), blue, "rising at (2, 4)");
  expect_color(pixel(image.get(), layout.to_image({1, 1})), blue, "rising at (1, 1)");
  expect_color(pixel(image.get(), layout.to_image({2, 0})), vermillion, "falling at (2, 0)");
  expect_color(pixel(image.get(), layout.to_image({1, 3})), vermillion, "falling at (1, 3)");
  // Where no series goes: white or a light grid line.
  const std::array<int, 3> empty = pixel(image.get(), layout.to_image({0.3, 2.2}));
  for (const int channel : empty) EXPECT_GE(channel, 200);
  // The image corner is background.
  expect_color(pixel(image.get(), {1, 1}), {255, 255, 255}, "corner");

  // Steps: the value 1 holds from x = 1 to x = 2, then jumps to 4; a line
  // would run diagonally through (1.5, 2.5) instead. Lines are 2 px wide,
  // so one of the pixels around a point on them is fully covered.
  const ChartSpec steps = crossing_series(ChartKind::steps);
  draw_chart(dir.file("steps.png"), steps);
  const Surface steps_image = read_png(dir.file("steps.png"));
  const ChartLayout steps_layout = chart_layout(steps);
  EXPECT_LE(color_distance_near(steps_image.get(), steps_layout.to_image({1.5, 1}), blue), 2);
  EXPECT_GE(color_distance_near(steps_image.get(), steps_layout.to_image({1.5, 2.5}), blue), 100);

  // Another size: the image follows.
  ChartSpec small = crossing_series();
  small.width = 400;
  small.height = 300;
  draw_chart(dir.file("small.png"), small);
  const Surface small_image = read_png(dir.file("small.png"));
  EXPECT_EQ(cairo_image_surface_get_width(small_image.get()), 400);
  EXPECT_EQ(cairo_image_surface_get_height(small_image.get()), 300);
}

TEST(Chart, WritesSvgAndPdf) {
  TempDir dir;
  const ChartSpec spec = crossing_series();
  draw_chart(dir.file("c.svg"), spec);
  const std::string svg = read_file(dir.file("c.svg"));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_TRUE(contains(svg, "<svg"));
  EXPECT_TRUE(contains(svg, "width=\"900pt\" height=\"600pt\""));
  EXPECT_TRUE(contains(svg, "</svg>"));
  draw_chart(dir.file("c.PDF"), spec);
  const std::string pdf = read_file(dir.file("c.PDF"));
  EXPECT_EQ(pdf.rfind("%PDF", 0), 0u);
  EXPECT_TRUE(contains(pdf, "%%EOF"));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"c.PDF", "c.svg"}));
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

  // A write that fails part-way (the file size limit is far below a PNG's
  // size) leaves the old file and no temporary.
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

  // A write that succeeds replaces it, with no temporary left.
  draw_chart(path, spec);
  EXPECT_EQ(read_file(path).rfind("\x89PNG", 0), 0u);
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
