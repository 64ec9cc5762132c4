// A structure: blocks (some of them fixed supports), applied point loads, and
// the contact interfaces between blocks, computed on demand and cached.
#pragma once

#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/block.hpp"
#include "structure/contact_detection.hpp"
#include "structure/interface.hpp"
#include "structure/overlap_detection.hpp"

namespace ashlar {

struct StructureBlock {
  BlockPtr block;
  bool support = false;  // fixed ground: no equilibrium equations
  std::string name;      // unique within the structure
};

// A concentrated force (N) applied to a block at a point (m).
struct PointLoad {
  int block = -1;  // 0-based
  Vec3 force = Vec3::Zero();
  Vec3 at = Vec3::Zero();
};

// One end of a cable: fixed to a block at a point, or (block -1) a junction
// where it meets the ends of other cables at the same point.
struct CableEnd {
  int block = -1;  // 0-based; a support block anchors the end
  Vec3 point = Vec3::Zero();  // m
};

// A tension-only element: force along its axis only, tension free, any
// compression penalised; weight mass_per_length * length * g, half at each
// end; tension at most max_tension (N).
struct Cable {
  CableEnd from, to;
  double mass_per_length = 0.0;  // kg/m
  double max_tension = std::numeric_limits<double>::infinity();  // N
};

class Structure {
public:
  // Adds a block and returns its 0-based index. A given name must be unused
  // (else InvalidArgument). An empty name becomes the block's own name, or
  // "block N" (N 1-based) when that is empty, with N appended when taken.
  int add(BlockPtr block, bool support = false, std::string name = {});
  // Throws InvalidArgument for a bad block index, a support block (loads
  // on fixed ground do nothing) or a non-finite value.
  void add_load(const PointLoad& load);
  void clear_loads() { loads_.clear(); }
  // Adds a cable and returns its 0-based index. Throws InvalidArgument for a
  // bad block index, an end point off its block, a zero length, a negative
  // mass or a non-positive tension bound.
  int add_cable(const Cable& cable);
  // Removes block i (0-based) and returns its entry. The blocks after it move
  // down one index, and so does every reference to them (loads, cable ends,
  // explicit interfaces); what refers to block i goes with it: its loads,
  // the cables with an end on it, its explicit interfaces. Names stay as
  // they are. Throws InvalidArgument for a bad index.
  StructureBlock remove(int i);

  int size() const { return static_cast<int>(blocks_.size()); }
  const StructureBlock& entry(int i) const { return blocks_.at(i); }
  const Block& block(int i) const { return *blocks_.at(i).block; }
  bool is_support(int i) const { return blocks_.at(i).support; }
  const std::string& name(int i) const { return blocks_.at(i).name; }
  // How messages name block i: "block 3 ('C-11-1')" (1-based), or "block 3"
  // when its name is the implicit one.
  std::string label(int i) const;
  int find(const std::string& name) const;  // -1 if absent
  const std::vector<StructureBlock>& entries() const { return blocks_; }
  const std::vector<PointLoad>& loads() const { return loads_; }
  const std::vector<Cable>& cables() const { return cables_; }
  // Moves both end points of cable `index` (the optimiser's design variables);
  // the same checks as add_cable.
  void set_cable_points(int index, const Vec3& from, const Vec3& to);
  Box3 bounds() const;

  // A planar structure lies in the x-z plane as an extrusion along y, with
  // every load in that plane: the analysis then balances only the in-plane
  // force and moment of each block (3 equations instead of 6).
  void set_planar(bool planar) { planar_ = planar; }
  bool planar() const { return planar_; }

  // Adds contacts that detection cannot find between blocks a and b
  // (0-based): a curved bed given as planar facets, a mortar joint modelled
  // as a plane, a chosen contact zone. Each polygon (at least 3 points, m)
  // becomes one interface: it must be planar within 1e-3 of its size and
  // simple. Its normal, from block a into block b, is `normal` when given
  // (the polygon is then projected on the plane through its centroid
  // perpendicular to it, and must be within 1 degree of that plane), else
  // the polygon's own normal turned to point from a's centroid towards
  // b's. Every polygon must lie by its blocks (its centroid within their
  // bounding boxes grown by 5 % of their size). From then on interfaces()
  // gives these in place of any it detects between a and b, and the pair
  // never counts as overlapping. Returns the number added; throws
  // InvalidArgument naming the polygon and the value at fault.
  int add_interface(int a, int b, const std::vector<std::vector<Vec3>>& polygons,
                    const std::optional<Vec3>& normal = std::nullopt);
  // The interfaces given by add_interface, in the order given.
  const std::vector<Interface>& explicit_interfaces() const { return explicit_; }
  // Throws InvalidArgument when the structure has explicit interfaces:
  // `caller` (gradients, optimisation, FEA) needs contacts found from the
  // geometry, which move and mesh with the blocks.
  void require_detected_interfaces(const std::string& caller) const;

  // Contact interfaces: the detected ones (recomputed only when blocks were
  // added or the options differ from the cached call) but between pairs
  // with explicit interfaces, and the explicit ones, sorted by (a, b).
  // Shared: what a caller holds stays valid whatever is asked next, and
  // calls from several threads are safe.
  std::shared_ptr<const std::vector<Interface>> interfaces(const ContactOptions& options = {}) const;
  // Pairs of blocks that interpenetrate by more than the contact tolerance
  // of `options`; cached and shared like the interfaces.
  std::shared_ptr<const std::vector<BlockOverlap>> overlaps(const ContactOptions& options = {}) const;
  // Throws GeometryError naming the overlapping pairs (the first few) and
  // how deep they overlap: an analysis of interpenetrating blocks would miss
  // the contacts between them. `caller` starts the message.
  void require_no_overlaps(const ContactOptions& options, const std::string& caller) const;
  // For each block in `which`, the nearest contact it misses within `reach`
  // (m) under `options` (see missed_contacts in contact_detection.hpp).
  std::vector<MissedContact> missed_contacts(const std::vector<int>& which, double reach,
                                             const ContactOptions& options = {}) const;
  // Pairs of blocks that would touch with a tolerance up to `reach` (m) but
  // do not under `options` (see near_misses in contact_detection.hpp).
  std::vector<NearMiss> near_misses(double reach, const ContactOptions& options = {}) const;
  // The contact tolerance (m) `options` stands for on this structure.
  double contact_tolerance(const ContactOptions& options = {}) const;
  // Throws InvalidArgument unless some block is not a support: an empty
  // structure, or ground alone, has nothing to analyse.
  void require_free_block(const std::string& caller) const;
  // Every block, in order, for the detection functions that take a list.
  std::vector<const Block*> block_pointers() const;

private:
  void check_cable(const Cable& cable, int index) const;
  Interface explicit_interface(int a, int b, std::vector<Vec3> polygon, const std::optional<Vec3>& normal,
                               const std::string& what) const;
  bool has_explicit_pair(int a, int b) const;

  std::vector<StructureBlock> blocks_;
  std::vector<PointLoad> loads_;
  std::vector<Cable> cables_;
  std::vector<Interface> explicit_;
  std::set<std::pair<int, int>> explicit_pairs_;  // (a, b), a < b, of explicit_: a lookup per detected contact
  std::unordered_map<std::string, int> index_by_name_;
  bool planar_ = false;

  // One value computed for the last contact options asked: a new one
  // replaces it, while callers keep theirs. Guarded for const use from
  // several threads; a copied structure starts with none.
  template <class Value>
  class ContactCache {
  public:
    ContactCache() = default;
    ContactCache(const ContactCache&) {}
    ContactCache& operator=(const ContactCache&) {
      clear();
      return *this;
    }
    // The value for `options`, computed by compute() when not cached
    // (structure.cpp, its only user).
    template <class Compute>
    std::shared_ptr<const Value> get(const ContactOptions& options, Compute compute) const;
    void clear() {
      const std::lock_guard<std::mutex> lock(mutex_);
      value_.reset();
    }

  private:
    mutable std::mutex mutex_;
    mutable ContactOptions options_;
    mutable std::shared_ptr<const Value> value_;
  };
  struct OverlapSet {
    double tolerance = 0.0;  // m, the one the options give for these blocks
    std::vector<BlockOverlap> pairs;
  };
  std::shared_ptr<const OverlapSet> overlap_set(const ContactOptions& options) const;
  ContactCache<std::vector<Interface>> interface_cache_;
  ContactCache<OverlapSet> overlap_cache_;
};

}  // namespace ashlar
