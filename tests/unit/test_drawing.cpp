// Elevation drawings (projection, faces, thrust line, files) and legends.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/color_legend.hpp"
#include "io/drawing.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A ground slab (support) under three 1 m cubes stacked along z, the top one
// shifted by `overhang` along x: the stack stands up to 0.5.
Structure stack(double overhang) {
  Structure s;
  s.add(box({4, 2, 0.5}, {0, 0, -0.25}), true, "ground");
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}), false, "base");
  s.add(box({1, 1, 0.5}, {overhang, 0, 0.75}), false, "top");
  return s;
}

// A semicircular arch in the x-z plane (depth 1 along y, centred on y = 0):
// centreline radius `radius`, `voussoirs` radial-jointed voussoirs from the
// right springing to the left, on two support boxes under the springings.
Structure arch(double radius, double thickness, int voussoirs) {
  const double inner = radius - thickness / 2, outer = radius + thickness / 2;
  const auto joint = [&](int k) {
    // The springing joints exactly horizontal, so they lie on the supports.
    const double angle = kPi * k / voussoirs;
    const double c = k == voussoirs ? -1.0 : std::cos(angle);
    const double s = k == voussoirs ? 0.0 : std::sin(angle);
    return std::vector<Vec3>{{inner * c, -0.5, inner * s}, {outer * c, -0.5, outer * s},
                             {outer * c, 0.5, outer * s}, {inner * c, 0.5, inner * s}};
  };
  Structure s;
  s.add(box({2 * thickness, 1, 0.5}, {radius, 0, -0.25}), true, "right support");
  s.add(box({2 * thickness, 1, 0.5}, {-radius, 0, -0.25}), true, "left support");
  for (int k = 0; k < voussoirs; ++k) {
    s.add(std::make_shared<const Block>(make_loft(joint(k), joint(k + 1))));
  }
  return s;
}

// One <path .../> element of a cairo SVG: its style (spaces removed, so
// that "fill:rgb(0%,0%,100%)" matches whatever cairo's spacing) and the
// points of its "M x y L x y ..." data.
struct SvgPath {
  std::string style;
  std::vector<Vec2> points;

  bool fill(const std::string& rgb) const {
    return contains(style, "fill:rgb(" + rgb + ")") || contains(style, "fill=\"rgb(" + rgb + ")\"");
  }
  bool stroke(const std::string& rgb) const {
    return contains(style, "stroke:rgb(" + rgb + ")") ||
           contains(style, "stroke=\"rgb(" + rgb + ")\"");
  }
};

// The paths drawn on the page (glyph definitions of the text left out).
std::vector<SvgPath> page_paths(const std::string& svg) {
  const std::string page = svg.substr(svg.find("<g id=\"surface"));
  std::vector<SvgPath> paths;
  const std::regex element("<path([^>]*)/>");
  const std::regex data("d=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), element);
       it != std::sregex_iterator(); ++it) {
    const std::string attributes = (*it)[1];
    SvgPath path;
    std::smatch d;
    std::regex_search(attributes, d, data);
    const std::string before_d = attributes.substr(0, d.position(0));
    for (char c : before_d) {
      if (c != ' ') path.style += c;
    }
    std::istringstream commands(d[1].str());
    std::string token;
    while (commands >> token) {
      if (token == "M" || token == "L") {
        double x, y;
        commands >> x >> y;
        path.points.emplace_back(x, y);
      }
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

int count_filled(const std::vector<SvgPath>& paths, const std::string& rgb) {
  int count = 0;
  for (const SvgPath& path : paths) count += path.fill(rgb);
  return count;
}

// The one stroked path with that colour.
SvgPath stroked(const std::vector<SvgPath>& paths, const std::string& rgb) {
  std::vector<SvgPath> found;
  for (const SvgPath& path : paths) {
    if (path.stroke(rgb) && contains(path.style, "fill:none")) found.push_back(path);
  }
  EXPECT_EQ(found.size(), 1u) << "paths stroked with rgb(" << rgb << ")";
  return found.empty() ? SvgPath{} : found.front();
}

// Width and height from a PNG's IHDR chunk (big-endian, bytes 16 to 23).
std::pair<int, int> png_size(const std::string& png) {
  const auto word = [&](size_t at) {
    int value = 0;
    for (size_t k = at; k < at + 4; ++k) value = value * 256 + static_cast<unsigned char>(png[k]);
    return value;
  };
  return {word(16), word(20)};
}

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);

}  // namespace

TEST(ElevationProjection, FitsPointsIntoTheAreaWithEqualScale) {
  // Front view: x to the right, z up. Extent 2 m x 1 m into 100 x 100 px at
  // (10, 20): 50 px per metre, centred vertically (25 px above and below).
  const std::vector<Vec3> points{{0, 0, 0}, {2, 3, 1}};
  const ElevationProjection front({0, 1, 0}, points, {10, 20, 100, 100});
  EXPECT_DOUBLE_EQ(front.scale(), 50.0);
  EXPECT_TRUE(front(Vec3(0, 0, 0)).isApprox(Vec2(10, 95)));
  EXPECT_TRUE(front(Vec3(2, 3, 1)).isApprox(Vec2(110, 45)));
  // Depth along the view does not move a point in the image.
  EXPECT_TRUE(front(Vec3(1, -7, 0.5)).isApprox(Vec2(60, 70)));
  EXPECT_DOUBLE_EQ(front.depth(Vec3(1, -7, 0.5)), -7.0);

  // Side view (looking along -x): y to the right. Extent 3 m x 1 m into
  // 100 x 100 px: 100/3 px per metre, centred vertically.
  const ElevationProjection side({-2, 0, 0}, points, {10, 20, 100, 100});
  EXPECT_DOUBLE_EQ(side.scale(), 100.0 / 3);
  EXPECT_TRUE(side.right().isApprox(Vec3(0, 1, 0)));
  EXPECT_TRUE(side(Vec3(0, 0, 0)).isApprox(Vec2(10, 70 + 50.0 / 3)));
  EXPECT_TRUE(side(Vec3(5, 3, 1)).isApprox(Vec2(110, 70 - 50.0 / 3)));

  // Looking along (1, 1, 0): image x along (1, -1, 0) / sqrt(2).
  const ElevationProjection oblique({1, 1, 0}, {{0, 0, 0}, {1, -1, 2}}, {0, 0, 200, 100});
  EXPECT_DOUBLE_EQ(oblique.scale(), 50.0);
  EXPECT_TRUE(oblique(Vec3(1, -1, 2)).isApprox(Vec2(100 + 25 * std::sqrt(2.0), 0)));
}

TEST(ElevationProjection, RejectsNonHorizontalViewsAndEmptyInput) {
  EXPECT_TRUE(contains(error_of([] { ElevationProjection({0, 1, 1}, {{0, 0, 0}}, {0, 0, 1, 1}); }),
                       "must be horizontal"));
  EXPECT_TRUE(contains(error_of([] { ElevationProjection({0, 0, 1}, {{0, 0, 0}}, {0, 0, 1, 1}); }),
                       "must be horizontal"));
  EXPECT_TRUE(contains(error_of([] { ElevationProjection({0, 1, 0}, {}, {0, 0, 1, 1}); }),
                       "no points"));
  EXPECT_TRUE(contains(
      error_of([] { ElevationProjection({0, 1, 0}, {{0, 0, 0}}, {0, 0, 0, 1}); }), "no room"));
}

TEST(Drawing, ScaleBarIsARoundLength) {
  EXPECT_DOUBLE_EQ(scale_bar_length(3.7), 2.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(0.9), 0.5);
  EXPECT_DOUBLE_EQ(scale_bar_length(12.0), 10.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(5.0), 5.0);
  EXPECT_DOUBLE_EQ(scale_bar_length(1.99), 1.0);
  EXPECT_NEAR(scale_bar_length(0.03), 0.02, 1e-15);
  EXPECT_TRUE(contains(error_of([] { scale_bar_length(0.0); }), "> 0"));
}

TEST(Drawing, LayoutLeavesMarginsTitleAndScaleBar) {
  // 1200 x 800: margins 4% of 800 = 32 px, text 16 px, the scale bar's band
  // 32 px at the bottom, the title's 35.2 px at the top.
  ElevationOptions options;
  const ImageRect area = elevation_area(options);
  EXPECT_DOUBLE_EQ(area.left, 32);
  EXPECT_DOUBLE_EQ(area.top, 32);
  EXPECT_DOUBLE_EQ(area.width, 1136);
  EXPECT_DOUBLE_EQ(area.height, 704);
  options.title = "title";
  EXPECT_DOUBLE_EQ(elevation_area(options).top, 32 + 35.2);
  EXPECT_DOUBLE_EQ(elevation_area(options).height, 704 - 35.2);
  options.width = 99;
  EXPECT_TRUE(contains(error_of([&] { elevation_area(options); }), "[100, 16384]"));
}

TEST(Drawing, FrontViewDrawsOneOutlinePerBlock) {
  TempDir dir;
  const Structure s = stack(0.3);
  ElevationOptions options;
  options.block_colors = {{0, 1, 0}, {0, 0, 1}, {0, 0, 1}};
  draw_elevation(s, dir.file("stack.svg"), options);
  const auto paths = page_paths(read_file(dir.file("stack.svg")));
  // Only the -y face of each box faces a viewer looking along +y.
  EXPECT_EQ(count_filled(paths, "0%,0%,100%"), 2);
  EXPECT_EQ(count_filled(paths, "0%,100%,0%"), 1);
  // The top block's front face, by hand: 284 px per metre, x = 0 at 600 px
  // and z = 0 at 455 px (see ThrustLineIsDrawnAtItsProjectedPoints).
  bool found = false;
  for (const SvgPath& path : paths) {
    if (!path.fill("0%,0%,100%")) continue;
    // cairo writes coordinates to 1/256 px.
    for (const Vec2& p : path.points) found |= (p - Vec2(600 + 284 * 0.8, 455 - 284)).norm() < 0.01;
  }
  EXPECT_TRUE(found) << "no corner at the top block's (0.8, 1.0)";

  // Looking along (1, 1, 0) shows two faces of each box (-x and -y).
  options.view_direction = {1, 1, 0};
  draw_elevation(s, dir.file("oblique.svg"), options);
  const auto oblique = page_paths(read_file(dir.file("oblique.svg")));
  EXPECT_EQ(count_filled(oblique, "0%,0%,100%"), 4);
  EXPECT_EQ(count_filled(oblique, "0%,100%,0%"), 2);
}

TEST(Drawing, ThrustLineIsDrawnAtItsProjectedPoints) {
  TempDir dir;
  const Structure s = stack(0.3);
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_TRUE(result.stable);
  ElevationOptions options;
  options.result = &result;
  options.thrust = true;
  options.thrust_color = {1, 0, 0};
  draw_elevation(s, dir.file("stack.svg"), options);
  const SvgPath thrust = stroked(page_paths(read_file(dir.file("stack.svg"))), "100%,0%,0%");
  // By hand: 1136 x 704 px for 4 m x 1.5 m gives 284 px per metre; the
  // middle (0, 0.25) sits at the area's centre (600, 384), so x = 0 at
  // 600 px and z = 0 at 455 px. The thrust runs from the ground joint
  // (centre of pressure under both blocks' centroid, x = 0.15) to the
  // joint under the top block (x = 0.3, z = 0.5).
  ASSERT_EQ(thrust.points.size(), 2u);
  EXPECT_NEAR(thrust.points[0].x(), 600 + 284 * 0.15, 0.01);
  EXPECT_NEAR(thrust.points[0].y(), 455, 0.01);
  EXPECT_NEAR(thrust.points[1].x(), 600 + 284 * 0.3, 0.01);
  EXPECT_NEAR(thrust.points[1].y(), 455 - 284 * 0.5, 0.01);
  // The same through the engine's own projection.
  const ElevationProjection projection = elevation_projection(s, options);
  const std::vector<Vec3> line = thrust_line(s, result);
  for (size_t k = 0; k < line.size(); ++k) {
    EXPECT_LT((thrust.points[k] - projection(line[k])).norm(), 0.01) << "point " << k;
  }
}

TEST(Drawing, ArchThrustLineRunsInsideTheRing) {
  TempDir dir;
  const double radius = 5, thickness = 1;
  const int voussoirs = 9;
  const Structure s = arch(radius, thickness, voussoirs);
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_TRUE(result.stable);
  ElevationOptions options;
  options.result = &result;
  options.thrust = true;
  options.forces = true;
  options.thrust_color = {1, 0, 0};
  options.title = "arch";
  draw_elevation(s, dir.file("arch.svg"), options);
  const auto paths = page_paths(read_file(dir.file("arch.svg")));
  const SvgPath thrust = stroked(paths, "100%,0%,0%");
  // One centre of pressure per joint, springing to springing.
  ASSERT_EQ(thrust.points.size(), static_cast<size_t>(voussoirs + 1));
  const ElevationProjection projection = elevation_projection(s, options);
  const Vec2 centre = projection(Vec3::Zero());
  for (const Vec2& p : thrust.points) {
    const double distance = (p - centre).norm() / projection.scale();
    EXPECT_GE(distance, radius - thickness / 2 - 1e-3);
    EXPECT_LE(distance, radius + thickness / 2 + 1e-3);
  }
  // One arrow head per interface (all in compression, so blue).
  EXPECT_EQ(count_filled(paths, "15%,35%,90%"), voussoirs + 1);
}

TEST(Drawing, ThrustPolylinesFollowChainsAndBranchAtBlocksWithMoreContacts) {
  // A chain: one polyline through thrust_line's points, in order.
  const Structure column = stack(0.3);
  const EquilibriumResult chain_result = analyze_equilibrium(column, {});
  const auto chain = thrust_polylines(column, chain_result);
  ASSERT_EQ(chain.size(), 1u);
  EXPECT_EQ(chain[0], thrust_line(column, chain_result));

  // A pier carrying two blocks side by side: its three contacts' centres of
  // pressure are joined pairwise, a closed triangle; the blocks on top add
  // nothing, since the solver leaves only a few newtons (0.05% of the
  // largest force) on their shared face. thrust_line's interface order
  // would run from the ground straight to a block on top and back across.
  Structure branching;
  branching.add(box({4, 2, 0.5}, {0, 0, -0.25}), true, "ground");
  branching.add(box({2, 1, 1}, {0, 0, 0.5}), false, "pier");
  branching.add(box({1, 1, 0.5}, {-0.5, 0, 1.25}), false, "left");
  branching.add(box({1, 1, 0.5}, {0.5, 0, 1.25}), false, "right");
  const EquilibriumResult result = analyze_equilibrium(branching, {});
  ASSERT_TRUE(result.stable);
  const auto lines = thrust_polylines(branching, result);
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].size(), 4u);
  EXPECT_TRUE(lines[0].front().isApprox(lines[0].back()));
  // Each block on top bears on the pier under its centroid (to the
  // millimetre: the few newtons between them shift it a little); the
  // ground under the whole, at x = 0.
  std::vector<double> xs;
  for (size_t k = 0; k < 3; ++k) xs.push_back(lines[0][k].x());
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], -0.5, 1e-3);
  EXPECT_NEAR(xs[1], 0.0, 1e-6);
  EXPECT_NEAR(xs[2], 0.5, 1e-3);

  // A block alone on the ground: a polyline of one point.
  Structure single;
  single.add(box({4, 2, 0.5}, {0, 0, -0.25}), true, "ground");
  single.add(box({1, 1, 1}, {0, 0, 0.5}), false, "block");
  const auto point = thrust_polylines(single, analyze_equilibrium(single, {}));
  ASSERT_EQ(point.size(), 1u);
  EXPECT_EQ(point[0].size(), 1u);
}

TEST(Drawing, PngHasTheRequestedSize) {
  TempDir dir;
  ElevationOptions options;
  options.width = 640;
  options.height = 480;
  draw_elevation(stack(0.3), dir.file("stack.PNG"), options);
  const std::string png = read_file(dir.file("stack.PNG"));
  EXPECT_EQ(png.substr(0, 8), kPngSignature);
  EXPECT_EQ(png_size(png), std::make_pair(640, 480));
}

TEST(Drawing, BadInputIsAnErrorAndWritesNothing) {
  TempDir dir;
  const Structure s = stack(0.3);
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ElevationOptions options;
  const std::string extension = error_of([&] { draw_elevation(s, dir.file("s.pdf"), options); });
  EXPECT_TRUE(contains(extension, ".svg") && contains(extension, ".png")) << extension;
  options.height = 20000;
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(s, dir.file("s.svg"), options); }),
                       "20000"));
  options.height = 800;
  options.thrust = true;
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(s, dir.file("s.svg"), options); }),
                       "thrust needs the result"));
  options.result = &result;
  Structure taller = stack(0.3);
  taller.add(box({1, 1, 0.5}, {0, 0, 1.25}));
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(taller, dir.file("t.svg"), options); }),
                       "3 blocks, this one has 4"));
  options.view_direction = {0, 0, -1};
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(s, dir.file("v.svg"), options); }),
                       "must be horizontal"));
  options.view_direction = {0, 1, 0};
  options.block_colors = {{0, 0, 1}};
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(s, dir.file("c.svg"), options); }),
                       "1 colours but the structure has 3"));
  EXPECT_TRUE(dir.entries().empty());
  options.block_colors.clear();
  EXPECT_TRUE(contains(error_of([&] { draw_elevation(s, dir.file("missing/s.svg"), options); }),
                       "missing/s.svg"));
}

TEST(Legend, TicksAreEvenAndReadable) {
  const auto labels = [](double lo, double hi) {
    std::vector<std::string> result;
    for (const LegendTick& tick : legend_ticks(lo, hi)) result.push_back(tick.label);
    return result;
  };
  using Labels = std::vector<std::string>;
  EXPECT_EQ(labels(0, 1), (Labels{"0", "0.25", "0.5", "0.75", "1"}));
  EXPECT_EQ(labels(0, 1000), (Labels{"0", "250", "500", "750", "1000"}));
  EXPECT_EQ(labels(-1, 1), (Labels{"-1", "-0.5", "0", "0.5", "1"}));
  EXPECT_EQ(labels(1.2, 5.6), (Labels{"1.2", "2.3", "3.4", "4.5", "5.6"}));
  EXPECT_EQ(labels(0, 4.0 / 3), (Labels{"0", "0.333", "0.667", "1", "1.333"}));
  EXPECT_EQ(labels(0.1, 0.3), (Labels{"0.1", "0.15", "0.2", "0.25", "0.3"}));
  EXPECT_EQ(labels(1e7, 2e7), (Labels{"1e+07", "1.25e+07", "1.5e+07", "1.75e+07", "2e+07"}));
  EXPECT_EQ(labels(0, 4e-5), (Labels{"0", "1e-05", "2e-05", "3e-05", "4e-05"}));
  const std::vector<LegendTick> ticks = legend_ticks(-0.3, 0.1, 3);
  ASSERT_EQ(ticks.size(), 3u);
  EXPECT_DOUBLE_EQ(ticks[0].value, -0.3);
  EXPECT_DOUBLE_EQ(ticks[1].value, -0.1);
  EXPECT_DOUBLE_EQ(ticks[2].value, 0.1);
  EXPECT_TRUE(contains(error_of([] { legend_ticks(1, 1); }), "lo < hi"));
  EXPECT_TRUE(contains(error_of([] { legend_ticks(0, NAN); }), "lo < hi"));
}

TEST(Legend, WritesImagesOfTheOrientationsSize) {
  TempDir dir;
  LegendOptions options;
  options.lo = 0;
  options.hi = 2.5;
  options.label = "load capacity (x own weight)";
  draw_legend(dir.file("v.png"), options);
  EXPECT_EQ(png_size(read_file(dir.file("v.png"))), std::make_pair(300, 600));
  options.vertical = false;
  options.map = "coolwarm";
  draw_legend(dir.file("h.png"), options);
  EXPECT_EQ(png_size(read_file(dir.file("h.png"))), std::make_pair(600, 150));
  options.width = 400;
  draw_legend(dir.file("h.svg"), options);
  const std::string svg = read_file(dir.file("h.svg"));
  EXPECT_TRUE(contains(svg, "width=\"400pt\"\n  height=\"150pt\"")) << svg.substr(0, 400);
  // The five ticks from lo to hi and the label are text.
  const std::vector<std::string> texts = svg_texts(svg);
  const std::vector<std::string> expected = {"0", "0.625", "1.25", "1.875", "2.5", options.label};
  for (const std::string& text : expected) {
    EXPECT_TRUE(has_text(texts, text)) << text;
  }

  options.map = "jet";
  EXPECT_TRUE(contains(error_of([&] { draw_legend(dir.file("x.png"), options); }), "viridis"));
  options.map = "magma";
  options.hi = -1;
  EXPECT_TRUE(contains(error_of([&] { draw_legend(dir.file("x.png"), options); }), "lo < hi"));
  options.hi = 1;
  EXPECT_TRUE(contains(error_of([&] { draw_legend(dir.file("x.jpg"), options); }), ".png"));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"h.png", "h.svg", "v.png"}));
}
