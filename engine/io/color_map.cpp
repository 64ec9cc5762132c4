// Colour maps as piecewise-linear tables of control points. The viridis and
// magma points are every 16th entry of matplotlib's 256-entry tables (van der
// Walt, Smith, Firing; CC0), coolwarm is every other point of Moreland's
// CoolWarmFloat33 table ("Diverging Color Maps for Scientific
// Visualization", 2009); between control points the maps differ from the
// published ones by less than one 8-bit step.
#include "io/color_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace ashlar {
namespace {

struct ControlPoint {
  double t;  // position in [0, 1], increasing along the table
  Rgb color;
};

struct ColorMap {
  const char* name;
  std::vector<ControlPoint> points;
};

// Positions of the sampled entries of a 256-entry table: 0, 16, ..., 240, 255.
constexpr double at_entry(int index) { return index / 255.0; }

const std::vector<ColorMap>& color_maps() {
  static const std::vector<ColorMap> maps = {
      {"viridis",
       {{at_entry(0), {0.267004, 0.004874, 0.329415}},
        {at_entry(16), {0.282327, 0.094955, 0.417331}},
        {at_entry(32), {0.278826, 0.175490, 0.483397}},
        {at_entry(48), {0.258965, 0.251537, 0.524736}},
        {at_entry(64), {0.229739, 0.322361, 0.545706}},
        {at_entry(80), {0.199430, 0.387607, 0.554642}},
        {at_entry(96), {0.172719, 0.448791, 0.557885}},
        {at_entry(112), {0.149039, 0.508051, 0.557250}},
        {at_entry(128), {0.127568, 0.566949, 0.550556}},
        {at_entry(144), {0.120638, 0.625828, 0.533488}},
        {at_entry(160), {0.157851, 0.683765, 0.501686}},
        {at_entry(176), {0.246070, 0.738910, 0.452024}},
        {at_entry(192), {0.369214, 0.788888, 0.382914}},
        {at_entry(208), {0.515992, 0.831158, 0.294279}},
        {at_entry(224), {0.678489, 0.863742, 0.189503}},
        {at_entry(240), {0.845561, 0.887322, 0.099702}},
        {at_entry(255), {0.993248, 0.906157, 0.143936}}}},
      {"magma",
       {{at_entry(0), {0.001462, 0.000466, 0.013866}},
        {at_entry(16), {0.039608, 0.031090, 0.133515}},
        {at_entry(32), {0.113094, 0.065492, 0.276784}},
        {at_entry(48), {0.211718, 0.061992, 0.418647}},
        {at_entry(64), {0.316654, 0.071690, 0.485380}},
        {at_entry(80), {0.414709, 0.110431, 0.504662}},
        {at_entry(96), {0.512831, 0.148179, 0.507648}},
        {at_entry(112), {0.613617, 0.181811, 0.498536}},
        {at_entry(128), {0.716387, 0.214982, 0.475290}},
        {at_entry(144), {0.816914, 0.255895, 0.436461}},
        {at_entry(160), {0.904281, 0.319610, 0.388137}},
        {at_entry(176), {0.960949, 0.418323, 0.359630}},
        {at_entry(192), {0.986700, 0.535582, 0.382210}},
        {at_entry(208), {0.996096, 0.653659, 0.446213}},
        {at_entry(224), {0.996898, 0.769591, 0.534892}},
        {at_entry(240), {0.992440, 0.884330, 0.640099}},
        {at_entry(255), {0.987053, 0.991438, 0.749504}}}},
      {"coolwarm",
       {{0.0, {0.2298057, 0.298717966, 0.753683153}},
        {0.0625, {0.30386891, 0.406535296, 0.84495867}},
        {0.125, {0.38301334, 0.50941904, 0.917387822}},
        {0.1875, {0.46666708, 0.604562568, 0.968154911}},
        {0.25, {0.552953156, 0.688929332, 0.995375608}},
        {0.3125, {0.639176211, 0.759599947, 0.998151185}},
        {0.375, {0.722193294, 0.813952739, 0.976574709}},
        {0.4375, {0.798691636, 0.849786142, 0.931688648}},
        {0.5, {0.865395197, 0.86541021, 0.865395561}},
        {0.5625, {0.924127593, 0.827384882, 0.774508472}},
        {0.625, {0.958852946, 0.769767752, 0.678007945}},
        {0.6875, {0.969954137, 0.694266682, 0.579375448}},
        {0.75, {0.958003065, 0.602842431, 0.481775914}},
        {0.8125, {0.923944917, 0.49730856, 0.387970225}},
        {0.875, {0.869186849, 0.378313092, 0.300267182}},
        {0.9375, {0.795631745, 0.24128379, 0.220525627}},
        {1.0, {0.705673158, 0.01555616, 0.150232812}}}},
      {"grayscale", {{0.0, {0.0, 0.0, 0.0}}, {1.0, {1.0, 1.0, 1.0}}}},
  };
  return maps;
}

std::string joined_names() {
  std::string names;
  for (const auto& name : color_map_names()) {
    if (!names.empty()) names += ", ";
    names += "'" + name + "'";
  }
  return names;
}

const ColorMap& find_map(const std::string& name) {
  for (const auto& map : color_maps()) {
    if (name == map.name) return map;
  }
  throw InvalidArgument("unknown colour map '" + name + "' (available: " + joined_names() + ")");
}

Rgb sample(const ColorMap& map, double t) {
  const auto& points = map.points;
  if (t <= points.front().t) return points.front().color;
  if (t >= points.back().t) return points.back().color;
  const auto upper = std::upper_bound(points.begin(), points.end(), t,
                                      [](double x, const ControlPoint& p) { return x < p.t; });
  const ControlPoint& b = *upper;
  const ControlPoint& a = *(upper - 1);
  const double w = (t - a.t) / (b.t - a.t);
  return {a.color.r + w * (b.color.r - a.color.r), a.color.g + w * (b.color.g - a.color.g),
          a.color.b + w * (b.color.b - a.color.b)};
}

}  // namespace

std::vector<Rgb> map_colors(const std::vector<double>& values, double lo, double hi,
                            const std::string& map_name) {
  const ColorMap& map = find_map(map_name);
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    std::ostringstream message;
    message << "colour range must be finite, got [" << lo << ", " << hi << "]";
    throw InvalidArgument(message.str());
  }
  // Halving both ends keeps the span finite even for ranges near DBL_MAX.
  const double half_span = hi / 2 - lo / 2;
  std::vector<Rgb> colors;
  colors.reserve(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const double value = values[i];
    if (std::isnan(value)) {
      throw InvalidArgument("cannot colour value " + std::to_string(i + 1) + " of " +
                            std::to_string(values.size()) + ": it is NaN");
    }
    // A zero-width range cannot order values; they all get the middle colour.
    const double t = half_span == 0.0 ? 0.5 : (value / 2 - lo / 2) / half_span;
    colors.push_back(sample(map, std::clamp(t, 0.0, 1.0)));
  }
  return colors;
}

std::pair<double, double> value_range(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double value : values) {
    if (!std::isfinite(value)) continue;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  if (lo > hi) return {0.0, 0.0};
  return {lo >= 0.0 ? 0.0 : lo, hi};
}

void check_color_map(const std::string& name) { find_map(name); }

const std::vector<std::string>& color_map_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> result;
    for (const auto& map : color_maps()) result.emplace_back(map.name);
    return result;
  }();
  return names;
}

}  // namespace ashlar
