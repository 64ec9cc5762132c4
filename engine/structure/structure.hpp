// A structure: blocks (some of them fixed supports), applied point loads, and
// the contact interfaces between blocks, computed on demand and cached.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/block.hpp"
#include "structure/contact_detection.hpp"
#include "structure/interface.hpp"

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

class Structure {
public:
  // Adds a block and returns its 0-based index. A given name must be unused
  // (else InvalidArgument). An empty name becomes the block's own name, or
  // "block N" (N 1-based) when that is empty, with N appended when taken.
  int add(BlockPtr block, bool support = false, std::string name = {});
  // Throws InvalidArgument for a bad block index, a support block (loads
  // on fixed ground do nothing) or a non-finite value.
  void add_load(const PointLoad& load);

  int size() const { return static_cast<int>(blocks_.size()); }
  const StructureBlock& entry(int i) const { return blocks_.at(i); }
  const Block& block(int i) const { return *blocks_.at(i).block; }
  bool is_support(int i) const { return blocks_.at(i).support; }
  const std::string& name(int i) const { return blocks_.at(i).name; }
  int find(const std::string& name) const;  // -1 if absent
  const std::vector<StructureBlock>& entries() const { return blocks_; }
  const std::vector<PointLoad>& loads() const { return loads_; }
  Box3 bounds() const;

  // A planar structure lies in the x-z plane as an extrusion along y, with
  // every load in that plane: the analysis then balances only the in-plane
  // force and moment of each block (3 equations instead of 6).
  void set_planar(bool planar) { planar_ = planar; }
  bool planar() const { return planar_; }

  // Contact interfaces; recomputed only when blocks were added or the
  // options differ from the cached call.
  const std::vector<Interface>& interfaces(const ContactOptions& options = {}) const;

private:
  std::vector<StructureBlock> blocks_;
  std::vector<PointLoad> loads_;
  std::unordered_map<std::string, int> index_by_name_;
  bool planar_ = false;

  struct InterfaceCache {
    bool valid = false;
    ContactOptions options;
    std::vector<Interface> interfaces;
  };
  mutable InterfaceCache cache_;
};

}  // namespace ashlar
