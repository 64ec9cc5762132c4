#include "geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ashlar {

Vec3 newell_normal(const std::vector<Vec3>& loop) {
  Vec3 n = Vec3::Zero();
  const size_t count = loop.size();
  if (count == 0) return n;
  // Relative to the first vertex: far from the origin the raw products lose digits.
  const Vec3& ref = loop[0];
  for (size_t i = 0; i < count; ++i) {
    n += (loop[i] - ref).cross(loop[(i + 1) % count] - ref);
  }
  return n;
}

PlaneFrame PlaneFrame::from_normal(const Vec3& origin, const Vec3& normal) {
  PlaneFrame f;
  f.origin = origin;
  f.normal = normal.normalized();
  // Seed e1 with the world axis least aligned with the normal, for a well
  // conditioned cross product.
  Vec3 seed = Vec3::UnitX();
  const Vec3 a = f.normal.cwiseAbs();
  if (a.y() <= a.x() && a.y() <= a.z()) seed = Vec3::UnitY();
  else if (a.z() <= a.x() && a.z() <= a.y()) seed = Vec3::UnitZ();
  f.e1 = (seed - f.normal * f.normal.dot(seed)).normalized();
  f.e2 = f.normal.cross(f.e1);
  return f;
}

Vec2 PlaneFrame::project(const Vec3& p) const {
  const Vec3 d = p - origin;
  return {d.dot(e1), d.dot(e2)};
}

Vec3 PlaneFrame::lift(const Vec2& q) const { return origin + q.x() * e1 + q.y() * e2; }

double signed_area(const Loop2& loop) {
  const size_t count = loop.size();
  if (count < 3) return 0.0;
  double twice = 0.0;
  const Vec2& ref = loop[0];
  for (size_t i = 1; i + 1 < count; ++i) {
    const Vec2 p = loop[i] - ref, q = loop[i + 1] - ref;
    twice += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * twice;
}

Vec2 area_centroid(const Loop2& loop) {
  const size_t count = loop.size();
  if (count == 0) return Vec2::Zero();
  const Vec2& ref = loop[0];
  double twice_area = 0.0;
  Vec2 moment = Vec2::Zero();
  for (size_t i = 1; i + 1 < count; ++i) {
    const Vec2 p = loop[i] - ref, q = loop[i + 1] - ref;
    const double cross = p.x() * q.y() - p.y() * q.x();
    twice_area += cross;
    moment += cross * (p + q) / 3.0;
  }
  if (twice_area == 0.0) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : loop) mean += p;
    return mean / static_cast<double>(count);
  }
  return ref + moment / twice_area;
}

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

bool is_convex(const Loop2& loop) {
  const size_t count = loop.size();
  if (count < 3) return false;
  double scale = 0.0;
  for (const Vec2& p : loop) scale = std::max(scale, (p - loop[0]).squaredNorm());
  // Turns smaller than this (relative to the loop's size squared) count as straight.
  const double straight = 1e-12 * scale;
  for (size_t i = 0; i < count; ++i) {
    const Vec2& p = loop[i];
    const Vec2& q = loop[(i + 1) % count];
    const Vec2& r = loop[(i + 2) % count];
    if (cross2(q - p, r - q) < -straight) return false;
  }
  return signed_area(loop) > 0.0;
}

Loop2 clip_convex(const Loop2& subject, const Loop2& clip) {
  Loop2 output = subject;
  const size_t count = clip.size();
  for (size_t i = 0; i < count && !output.empty(); ++i) {
    const Vec2& a = clip[i];
    const Vec2 edge = clip[(i + 1) % count] - a;
    const Loop2 input = std::move(output);
    output.clear();
    const size_t n = input.size();
    for (size_t j = 0; j < n; ++j) {
      const Vec2& p = input[j];
      const Vec2& q = input[(j + 1) % n];
      const double sp = cross2(edge, p - a);
      const double sq = cross2(edge, q - a);
      if (sp >= 0.0) output.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) {
        const double t = sp / (sp - sq);
        output.push_back(p + t * (q - p));
      }
    }
  }
  // Drop repeated points that clipping along shared edges produces.
  Loop2 cleaned;
  for (const Vec2& p : output) {
    if (cleaned.empty() || (p - cleaned.back()).squaredNorm() > 0.0) cleaned.push_back(p);
  }
  while (cleaned.size() > 1 && (cleaned.front() - cleaned.back()).squaredNorm() == 0.0) {
    cleaned.pop_back();
  }
  if (cleaned.size() < 3) cleaned.clear();
  return cleaned;
}

double perimeter(const Loop2& loop) {
  double length = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) length += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  return length;
}

double least_width(const Loop2& loop) {
  // Andrew's monotone chain: the hull counter-clockwise, collinear points dropped.
  Loop2 points = loop;
  std::sort(points.begin(), points.end(), [](const Vec2& p, const Vec2& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  });
  if (points.size() < 3) return 0.0;
  Loop2 hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point is the first again
  const size_t n = hull.size();
  if (n < 3) return 0.0;
  // The least width is attained with one line along a hull edge: for each
  // edge the farthest hull point, advanced monotonically (O(n)).
  double width = std::numeric_limits<double>::infinity();
  size_t far = 1;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = hull[i];
    const Vec2 edge = hull[(i + 1) % n] - p;
    const double length = edge.norm();
    if (length == 0.0) continue;
    auto height = [&](size_t j) { return cross2(edge, hull[j % n] - p); };
    while (height(far + 1) > height(far)) ++far;
    width = std::min(width, height(far) / length);
  }
  return std::isfinite(width) ? width : 0.0;
}

}  // namespace ashlar
