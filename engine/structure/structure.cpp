#include "structure/structure.hpp"

#include "core/error.hpp"

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
  cache_.valid = false;
  return index;
}

void Structure::add_load(const PointLoad& load) {
  if (load.block < 0 || load.block >= size()) {
    throw InvalidArgument("load: block " + std::to_string(load.block + 1) +
                          " does not exist (the structure has " + std::to_string(size()) +
                          " blocks)");
  }
  if (blocks_[load.block].support) {
    throw InvalidArgument("load: block " + std::to_string(load.block + 1) + " ('" +
                          blocks_[load.block].name +
                          "') is a support; a load on fixed ground has no effect");
  }
  if (!load.force.allFinite()) throw InvalidArgument("load: force must be finite");
  if (!load.at.allFinite()) throw InvalidArgument("load: point of application must be finite");
  loads_.push_back(load);
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

const std::vector<Interface>& Structure::interfaces(const ContactOptions& options) const {
  if (!cache_.valid || cache_.options.tolerance != options.tolerance ||
      cache_.options.relative_tolerance != options.relative_tolerance) {
    std::vector<const Block*> blocks;
    blocks.reserve(blocks_.size());
    for (const StructureBlock& entry : blocks_) blocks.push_back(entry.block.get());
    cache_.interfaces = detect_interfaces(blocks, options);
    cache_.options = options;
    cache_.valid = true;
  }
  return cache_.interfaces;
}

}  // namespace ashlar
