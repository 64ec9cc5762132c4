#include "dynamics/simulation_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {

namespace {

void check_frames(const Structure& structure, const SimulationResult& result) {
  if (result.poses.empty() || result.poses.front().size() != static_cast<std::size_t>(structure.size())) {
    throw InvalidArgument("simulation summary: the result's frames do not match the structure");
  }
}

}  // namespace

SimulationSummary summarize(const Structure& structure, const SimulationResult& result, const SummaryOptions& options) {
  check_frames(structure, result);
  if (!(options.moved_fraction > 0.0) || !std::isfinite(options.moved_fraction)) {
    throw InvalidArgument("simulation summary: moved_fraction must be > 0, got " + shortest_number(options.moved_fraction));
  }
  if (!(options.fall_fraction > 0.0) || !std::isfinite(options.fall_fraction)) {
    throw InvalidArgument("simulation summary: fall_fraction must be > 0, got " + shortest_number(options.fall_fraction));
  }
  if (options.fall_level && !std::isfinite(*options.fall_level)) {
    throw InvalidArgument("simulation summary: fall_level must be a finite height (m), got " +
                          shortest_number(*options.fall_level));
  }
  const int n = static_cast<int>(structure.size());
  const std::vector<RigidPose>& start = result.poses.front();
  const std::vector<RigidPose>& end = result.poses.back();
  SimulationSummary summary;
  summary.peak_displacement = result.displacement;
  summary.peak_displacement.resize(static_cast<std::size_t>(n), 0.0);
  summary.residual_displacement.assign(static_cast<std::size_t>(n), 0.0);
  std::vector<double> fall_time(static_cast<std::size_t>(n), -1.0);
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) {
      summary.peak_displacement[i] = 0.0;
      continue;
    }
    const Block& block = structure.block(i);
    summary.residual_displacement[i] = vertex_distance(block, end[i], start[i]);
    if (summary.peak_displacement[i] > summary.peak) {
      summary.peak = summary.peak_displacement[i];
      summary.peak_block = i;
    }
    if (summary.residual_displacement[i] > summary.residual) {
      summary.residual = summary.residual_displacement[i];
      summary.residual_block = i;
    }
    const Vec3 extent = block.bounds().hi - block.bounds().lo;
    const double drop = options.fall_fraction * extent.minCoeff();
    const double moved = options.moved_fraction * block.bounds().diagonal();
    for (std::size_t k = 0; k < result.poses.size(); ++k) {
      const RigidPose& pose = result.poses[k][i];
      const double t = result.times[k];
      if ((!summary.first_movement || t < *summary.first_movement) && vertex_distance(block, pose, start[i]) > moved) {
        summary.first_movement = t;
      }
      const double z = pose.position.z();
      const bool below_level = options.fall_level && start[i].position.z() >= *options.fall_level && z < *options.fall_level;
      if (z < start[i].position.z() - drop || below_level) {
        fall_time[i] = t;
        break;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (fall_time[i] >= 0.0) summary.fallen.push_back(i);
  }
  std::stable_sort(summary.fallen.begin(), summary.fallen.end(),
                   [&](int a, int b) { return fall_time[a] < fall_time[b]; });
  for (const int i : summary.fallen) summary.fall_times.push_back(fall_time[i]);
  if (!summary.fall_times.empty()) summary.collapse_time = summary.fall_times.front();
  return summary;
}

std::vector<double> displacement_history(const Structure& structure, const SimulationResult& result, int block) {
  check_frames(structure, result);
  std::vector<double> history;
  history.reserve(result.poses.size());
  for (const std::vector<RigidPose>& frame : result.poses) {
    history.push_back(vertex_distance(structure.block(block), frame[block], result.poses.front()[block]));
  }
  return history;
}

Drift drift(const Structure& structure, const SimulationResult& result, const std::vector<int>& blocks) {
  check_frames(structure, result);
  if (blocks.empty()) throw InvalidArgument("drift: no block given");
  const int n = static_cast<int>(structure.size());
  for (const int i : blocks) {
    if (i < 0 || i >= n) throw InvalidArgument("drift: block " + std::to_string(i + 1) + " is not in the structure");
    if (structure.is_support(i)) {
      throw InvalidArgument("drift: block " + std::to_string(i + 1) + " is a support, which does not move");
    }
  }
  const std::vector<RigidPose>& start = result.poses.front();
  double base = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) continue;
    for (const Vec3& p : structure.block(i).vertices()) {
      base = std::min(base, start[i].apply(p, structure.block(i).centroid()).z());
    }
  }
  const auto mean_centroid = [&](const std::vector<RigidPose>& frame) {
    Vec3 sum = Vec3::Zero();
    for (const int i : blocks) sum += frame[i].position;
    return Vec3(sum / static_cast<double>(blocks.size()));
  };
  const Vec3 origin = mean_centroid(start);
  Drift d;
  d.height = origin.z() - base;
  if (!(d.height > 0.0)) throw InvalidArgument("drift: the blocks' centroids are not above the base of the structure");
  for (const std::vector<RigidPose>& frame : result.poses) {
    const Vec3 shift = mean_centroid(frame) - origin;
    d.values.push_back(std::hypot(shift.x(), shift.y()) / d.height);
  }
  d.peak = *std::max_element(d.values.begin(), d.values.end());
  d.residual = d.values.back();
  return d;
}

}  // namespace ashlar
