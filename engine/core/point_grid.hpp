// Points (or boxes) bucketed in cubic cells for neighbour queries: welding
// mesh vertices, finding design nodes that coincide, finding the contact
// features (vertices, edges) near a point of a contact plane.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

// Buckets points in cubic cells of side `cell` for neighbour queries in
// time proportional to the cells (or the occupied cells) they cover.
class PointGrid {
public:
  PointGrid(const Vec3& origin, double cell) : origin_(origin), cell_(cell) {}

  void insert(const Vec3& p, int id) { cells_[key(p)].push_back(id); }
  // `id` in every cell the box [lo, hi] overlaps (once per cell, when the
  // same id is inserted in a row, as the pieces of one edge are).
  void insert_box(const Vec3& lo, const Vec3& hi, int id) {
    const Key first = key(lo), last = key(hi);
    for (Key k = first; k[0] <= last[0]; ++k[0]) {
      for (k[1] = first[1]; k[1] <= last[1]; ++k[1]) {
        for (k[2] = first[2]; k[2] <= last[2]; ++k[2]) {
          std::vector<int>& ids = cells_[k];
          if (ids.empty() || ids.back() != id) ids.push_back(id);
        }
      }
    }
  }

  // The ids in the cells that overlap the box [lo, hi]: every point inside
  // the box, and some near it.
  void for_each_in(const Vec3& lo, const Vec3& hi, const std::function<void(int)>& visit) const {
    const Key first = key(lo), last = key(hi);
    double cells = 1.0;
    for (int axis = 0; axis < 3; ++axis) cells *= static_cast<double>(last[axis] - first[axis] + 1);
    const auto inside = [&](const Key& k) {
      for (int axis = 0; axis < 3; ++axis) {
        if (k[axis] < first[axis] || k[axis] > last[axis]) return false;
      }
      return true;
    };
    if (cells > static_cast<double>(cells_.size())) {
      for (const auto& [k, ids] : cells_) {
        if (!inside(k)) continue;
        for (int id : ids) visit(id);
      }
      return;
    }
    for (Key k = first; k[0] <= last[0]; ++k[0]) {
      for (k[1] = first[1]; k[1] <= last[1]; ++k[1]) {
        for (k[2] = first[2]; k[2] <= last[2]; ++k[2]) {
          const auto cell = cells_.find(k);
          if (cell == cells_.end()) continue;
          for (int id : cell->second) visit(id);
        }
      }
    }
  }

  void for_each_near(const Vec3& p, double radius, const std::function<void(int)>& visit) const {
    for_each_in(p - Vec3::Constant(radius), p + Vec3::Constant(radius), visit);
  }

private:
  using Key = std::array<std::int64_t, 3>;
  struct KeyHash {
    size_t operator()(const Key& k) const {
      const auto bits = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
      return static_cast<size_t>(bits(k[0]) * 73856093u ^ bits(k[1]) * 19349663u ^
                                 bits(k[2]) * 83492791u);
    }
  };
  Key key(const Vec3& p) const {
    const Vec3 q = (p - origin_) / cell_;
    return {static_cast<std::int64_t>(std::floor(q.x())),
            static_cast<std::int64_t>(std::floor(q.y())),
            static_cast<std::int64_t>(std::floor(q.z()))};
  }

  Vec3 origin_;
  double cell_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

}  // namespace ashlar
