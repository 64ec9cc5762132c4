#include "structure/structure.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/text.hpp"
#include "geometry/polygon.hpp"
#include "geometry/polygon_boolean.hpp"

namespace ashlar {

int Structure::add(BlockPtr block, bool support, std::string name) {
  if (!block) throw InvalidArgument("structure add: no block given");
  const int index = size();
  if (!name.empty()) {
    if (find(name) >= 0) {
      throw InvalidArgument("structure add: the name '" + name + "' is already used by block " +
                            std::to_string(find(name) + 1) + "; block names must be unique");
    }
  } else {
    // Implicit names come from the block; copies of one named block get the
    // block's index appended so that every name still finds one block.
    name = block->name().empty() ? "block " + std::to_string(index + 1) : block->name();
    if (find(name) >= 0) name += " " + std::to_string(index + 1);
    while (find(name) >= 0) name += "'";
  }
  blocks_.push_back({std::move(block), support, name});
  index_by_name_.emplace(blocks_.back().name, index);
  interface_cache_.clear();
  overlap_cache_.clear();
  return index;
}

void Structure::add_load(const PointLoad& load) {
  if (load.block < 0 || load.block >= size()) {
    throw InvalidArgument("load: block " + std::to_string(load.block + 1) +
                          " does not exist (the structure has " + std::to_string(size()) +
                          " blocks)");
  }
  if (blocks_[load.block].support) {
    throw InvalidArgument("load: " + label(load.block) + " is a support; a load on fixed ground has no effect");
  }
  if (!load.force.allFinite()) throw InvalidArgument("load: force must be finite");
  if (!load.at.allFinite()) throw InvalidArgument("load: point of application must be finite");
  loads_.push_back(load);
}

namespace {

std::string cable_end_name(int cable, const char* end) {
  return "cable " + std::to_string(cable + 1) + " '" + end + "'";
}

}  // namespace

void Structure::check_cable(const Cable& cable, int index) const {
  const struct { const CableEnd& end; const char* name; } ends[2] = {{cable.from, "from"},
                                                                     {cable.to, "to"}};
  for (const auto& [end, end_name] : ends) {
    const std::string what = cable_end_name(index, end_name);
    if (end.block < -1 || end.block >= size()) {
      throw InvalidArgument(what + ": block " + std::to_string(end.block + 1) +
                            " does not exist (the structure has " + std::to_string(size()) +
                            " blocks)");
    }
    if (!end.point.allFinite()) throw InvalidArgument(what + ": point must be finite");
    if (end.block >= 0) {
      // An attachment point must be on the block: within its bounding box,
      // give or take a relative 1e-6 of its size.
      const Box3& box = block(end.block).bounds();
      const double slack = 1e-6 * box.diagonal();
      if ((end.point.array() < box.lo.array() - slack).any() ||
          (end.point.array() > box.hi.array() + slack).any()) {
        throw InvalidArgument(what + ": point is not on block " + std::to_string(end.block + 1) +
                              " ('" + name(end.block) + "'), which spans from (" +
                              std::to_string(box.lo.x()) + ", " + std::to_string(box.lo.y()) +
                              ", " + std::to_string(box.lo.z()) + ") to (" +
                              std::to_string(box.hi.x()) + ", " + std::to_string(box.hi.y()) +
                              ", " + std::to_string(box.hi.z()) + ")");
      }
    }
  }
  const std::string what = "cable " + std::to_string(index + 1);
  if (!((cable.to.point - cable.from.point).norm() > 0.0)) {
    throw InvalidArgument(what + ": its two ends are at the same point (zero length)");
  }
  if (!std::isfinite(cable.mass_per_length) || cable.mass_per_length < 0.0) {
    throw InvalidArgument(what + ": mass_per_length must be a finite number >= 0 (kg/m)");
  }
  if (std::isnan(cable.max_tension) || cable.max_tension <= 0.0) {
    throw InvalidArgument(what + ": max_tension must be a number > 0 (N), or nil for no limit");
  }
  if (cable.from.block >= 0 && cable.from.block == cable.to.block) {
    throw InvalidArgument(what + ": both ends are on block " + std::to_string(cable.from.block + 1) +
                          "; a cable within one block carries nothing");
  }
}

int Structure::add_cable(const Cable& cable) {
  const int index = static_cast<int>(cables_.size());
  check_cable(cable, index);
  cables_.push_back(cable);
  return index;
}

StructureBlock Structure::remove(int i) {
  if (i < 0 || i >= size()) {
    throw InvalidArgument("remove: block " + std::to_string(i + 1) + " does not exist (the structure has " +
                          std::to_string(size()) + " blocks)");
  }
  // The index a reference to block j has once block i is gone.
  const auto renumber = [i](int& j) { j -= j > i ? 1 : 0; };
  loads_.erase(std::remove_if(loads_.begin(), loads_.end(), [i](const PointLoad& load) { return load.block == i; }),
               loads_.end());
  for (PointLoad& load : loads_) renumber(load.block);
  cables_.erase(std::remove_if(cables_.begin(), cables_.end(),
                               [i](const Cable& cable) { return cable.from.block == i || cable.to.block == i; }),
                cables_.end());
  for (Cable& cable : cables_) {
    renumber(cable.from.block);
    renumber(cable.to.block);
  }
  explicit_.erase(std::remove_if(explicit_.begin(), explicit_.end(),
                                 [i](const Interface& contact) { return contact.a == i || contact.b == i; }),
                  explicit_.end());
  explicit_pairs_.clear();
  for (Interface& contact : explicit_) {
    renumber(contact.a);
    renumber(contact.b);
    explicit_pairs_.insert({contact.a, contact.b});
  }
  StructureBlock removed = std::move(blocks_[i]);
  blocks_.erase(blocks_.begin() + i);
  index_by_name_.erase(removed.name);
  for (auto& [name, index] : index_by_name_) renumber(index);
  interface_cache_.clear();
  overlap_cache_.clear();
  return removed;
}

void Structure::set_cable_points(int index, const Vec3& from, const Vec3& to) {
  if (index < 0 || index >= static_cast<int>(cables_.size())) {
    throw InvalidArgument("cable " + std::to_string(index + 1) + " does not exist");
  }
  Cable moved = cables_[index];
  moved.from.point = from;
  moved.to.point = to;
  check_cable(moved, index);
  cables_[index] = moved;
}

std::string Structure::label(int i) const {
  const std::string number = "block " + std::to_string(i + 1);
  return name(i) == number ? number : number + " ('" + name(i) + "')";
}

int Structure::find(const std::string& name) const {
  const auto it = index_by_name_.find(name);
  return it == index_by_name_.end() ? -1 : it->second;
}

Box3 Structure::bounds() const {
  Box3 box;
  for (const StructureBlock& entry : blocks_) box.add(entry.block->bounds());
  return box;
}

std::vector<MissedContact> Structure::missed_contacts(const std::vector<int>& which, double reach,
                                                     const ContactOptions& options) const {
  return ashlar::missed_contacts(block_pointers(), which, reach, options);
}

std::vector<NearMiss> Structure::near_misses(double reach, const ContactOptions& options) const {
  std::vector<NearMiss> found = ashlar::near_misses(block_pointers(), reach, options);
  found.erase(std::remove_if(found.begin(), found.end(),
                             [&](const NearMiss& pair) { return has_explicit_pair(pair.a, pair.b); }),
              found.end());
  return found;
}

double Structure::contact_tolerance(const ContactOptions& options) const {
  return effective_tolerance(block_pointers(), options);
}

std::vector<const Block*> Structure::block_pointers() const {
  std::vector<const Block*> blocks;
  blocks.reserve(blocks_.size());
  for (const StructureBlock& entry : blocks_) blocks.push_back(entry.block.get());
  return blocks;
}

Interface Structure::explicit_interface(int a, int b, std::vector<Vec3> polygon,
                                        const std::optional<Vec3>& normal, const std::string& what) const {
  if (polygon.size() < 3) {
    throw InvalidArgument(what + ": expected at least 3 points, got " + std::to_string(polygon.size()));
  }
  for (size_t k = 0; k < polygon.size(); ++k) {
    if (!polygon[k].allFinite()) {
      throw InvalidArgument(what + ": point " + std::to_string(k + 1) + " is not finite");
    }
  }
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : polygon) centroid += p;
  centroid /= static_cast<double>(polygon.size());
  Box3 extent;
  for (const Vec3& p : polygon) extent.add(p);
  const double size = extent.diagonal();
  const Vec3 own_normal = newell_normal(polygon);
  if (!(own_normal.norm() > 1e-12 * size * size)) {
    throw InvalidArgument(what + ": its points enclose no area (collinear or repeated points)");
  }
  const double allowed = 1e-3 * size;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const double off = std::abs(own_normal.normalized().dot(polygon[k] - centroid));
    if (off > allowed) {
      throw InvalidArgument(what + ": not planar: point " + std::to_string(k + 1) + " is " + message_number(off) +
                            " m off its plane (allowed: " + message_number(allowed) + " m, 1e-3 of its size)");
    }
  }
  Vec3 n = own_normal.normalized();
  if (normal) {
    if (!normal->allFinite() || !(normal->norm() > 0.0)) {
      throw InvalidArgument(what + ": normal must be a finite, non-zero vector");
    }
    const Vec3 given = normal->normalized();
    const double angle = std::acos(std::min(1.0, std::abs(given.dot(n))));
    if (angle > kPi / 180.0) {
      throw InvalidArgument(what + ": the polygon's plane is " + message_number(angle * 180.0 / kPi) +
                            " degrees off perpendicular to the given normal (allowed: 1 degree)");
    }
    n = given;
  } else if (n.dot(block(b).centroid() - block(a).centroid()) < 0.0) {
    n = -n;
  }
  // By its blocks: a polygon away from them would apply forces at a distance.
  for (int end : {a, b}) {
    const Box3& box = block(end).bounds();
    const double grow = 0.05 * box.diagonal();
    if ((centroid.array() < box.lo.array() - grow).any() || (centroid.array() > box.hi.array() + grow).any()) {
      const Vec3 nearest = centroid.cwiseMax(box.lo).cwiseMin(box.hi);
      throw InvalidArgument(what + ": it lies " + message_number((centroid - nearest).norm()) + " m from " + label(end) +
                            " (its centroid must be within the block's bounding box grown by 5 % of its size)");
    }
  }
  if (a > b) {
    std::swap(a, b);
    n = -n;
  }
  const PlaneFrame frame = PlaneFrame::from_normal(centroid, n);
  Loop2 flat;
  for (const Vec3& p : polygon) flat.push_back(frame.project(p));
  if (signed_area(flat) < 0.0) std::reverse(flat.begin(), flat.end());
  if (!is_convex(flat) && !is_simple_loop(flat)) {
    throw InvalidArgument(what + ": its outline crosses itself: expected a simple polygon");
  }
  Interface contact;
  contact.a = a;
  contact.b = b;
  contact.normal = n;
  contact.area = signed_area(flat);
  contact.center = frame.lift(area_centroid(flat));
  for (const Vec2& q : flat) contact.vertices.push_back(frame.lift(q));
  set_frame_along_longest_edge(contact);
  contact.is_explicit = true;
  return contact;
}

int Structure::add_interface(int a, int b, const std::vector<std::vector<Vec3>>& polygons,
                             const std::optional<Vec3>& normal) {
  for (int end : {a, b}) {
    if (end < 0 || end >= size()) {
      throw InvalidArgument("interface: block " + std::to_string(end + 1) + " does not exist (the structure has " +
                            std::to_string(size()) + " blocks)");
    }
  }
  if (a == b) throw InvalidArgument("interface: a and b are both " + label(a) + "; expected two blocks");
  if (polygons.empty()) throw InvalidArgument("interface: expected at least one polygon, got none");
  std::vector<Interface> added;
  for (size_t k = 0; k < polygons.size(); ++k) {
    const std::string what = "interface between " + label(a) + " and " + label(b) + ", polygon " +
                             std::to_string(k + 1);
    added.push_back(explicit_interface(a, b, polygons[k], normal, what));
  }
  for (const Interface& contact : added) explicit_pairs_.insert({contact.a, contact.b});
  explicit_.insert(explicit_.end(), added.begin(), added.end());
  interface_cache_.clear();
  overlap_cache_.clear();
  return static_cast<int>(added.size());
}

bool Structure::has_explicit_pair(int a, int b) const {
  if (a > b) std::swap(a, b);
  return explicit_pairs_.count({a, b}) > 0;
}

void Structure::require_detected_interfaces(const std::string& caller) const {
  if (explicit_.empty()) return;
  throw InvalidArgument(caller + ": the structure has " + std::to_string(explicit_.size()) +
                        (explicit_.size() == 1 ? " explicit interface" : " explicit interfaces") +
                        " (from s:add_interface or a file's stored interfaces, the first between " +
                        label(explicit_[0].a) + " and " + label(explicit_[0].b) + "); " + caller +
                        " needs contacts found from the geometry, which move with the blocks (import a COMPAS "
                        "file with interfaces = \"detect\")");
}

template <class Value>
template <class Compute>
std::shared_ptr<const Value> Structure::ContactCache<Value>::get(const ContactOptions& options,
                                                                 Compute compute) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!value_ || !same_contacts(options_, options)) {
    value_ = std::make_shared<const Value>(compute());
    options_ = options;
  }
  return value_;
}

std::shared_ptr<const std::vector<Interface>> Structure::interfaces(const ContactOptions& options) const {
  return interface_cache_.get(options, [&] {
    std::vector<Interface> found = detect_interfaces(block_pointers(), options);
    if (!explicit_.empty()) {
      found.erase(std::remove_if(found.begin(), found.end(),
                                 [&](const Interface& contact) { return has_explicit_pair(contact.a, contact.b); }),
                  found.end());
      found.insert(found.end(), explicit_.begin(), explicit_.end());
      std::stable_sort(found.begin(), found.end(), [](const Interface& x, const Interface& y) {
        return std::tie(x.a, x.b) < std::tie(y.a, y.b);
      });
      found.shrink_to_fit();
    }
    return found;
  });
}

std::shared_ptr<const Structure::OverlapSet> Structure::overlap_set(const ContactOptions& options) const {
  return overlap_cache_.get(options, [&] {
    const std::vector<const Block*> blocks = block_pointers();
    OverlapSet set;
    set.tolerance = effective_tolerance(blocks, options);
    set.pairs = detect_overlaps(blocks, set.tolerance);
    set.pairs.erase(std::remove_if(set.pairs.begin(), set.pairs.end(),
                                   [&](const BlockOverlap& pair) { return has_explicit_pair(pair.a, pair.b); }),
                    set.pairs.end());
    return set;
  });
}

std::shared_ptr<const std::vector<BlockOverlap>> Structure::overlaps(const ContactOptions& options) const {
  const std::shared_ptr<const OverlapSet> set = overlap_set(options);
  return {set, &set->pairs};  // shares the set's ownership
}

void Structure::require_free_block(const std::string& caller) const {
  if (blocks_.empty()) {
    throw InvalidArgument(caller + ": the structure is empty: expected at least one block that is "
                                   "not a support (add blocks with s:add)");
  }
  const bool free = std::any_of(blocks_.begin(), blocks_.end(),
                                [](const StructureBlock& entry) { return !entry.support; });
  if (!free) {
    throw InvalidArgument(caller + ": all " + std::to_string(size()) +
                          " blocks are supports: expected at least one block that is not a support");
  }
}

void Structure::require_no_overlaps(const ContactOptions& options, const std::string& caller) const {
  const std::shared_ptr<const OverlapSet> set = overlap_set(options);
  const std::vector<BlockOverlap>& found = set->pairs;
  if (found.empty()) return;
  constexpr size_t kListed = 3;
  std::ostringstream message;
  message.precision(3);
  message << caller << ": " << label(found[0].a) << " and " << label(found[0].b) << " overlap by "
          << found[0].depth << " m";
  for (size_t k = 1; k < std::min(found.size(), kListed); ++k) {
    message << "; " << label(found[k].a) << " and " << label(found[k].b) << " by "
            << found[k].depth << " m";
  }
  if (found.size() > kListed) message << "; and " << found.size() - kListed << " more pairs";
  message << " (expected blocks that touch along faces, not interpenetrate; contact tolerance "
          << set->tolerance << " m)";
  throw GeometryError(message.str());
}

}  // namespace ashlar
