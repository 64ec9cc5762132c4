// Fuzz target: mesh import as ashlar.import does it, assimp's reader, the
// scene walk, welding, block validation and adding the blocks to a
// structure. The first byte picks the file format (the engine reads files
// by path, and assimp picks its reader by extension) and the weld
// tolerance; the rest is the file. Bad files must give an ashlar::Error (an
// IoError, or a GeometryError naming the object); any other exception
// escapes and counts as a crash.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "io/mesh_io.hpp"
#include "scratch_folder.hpp"
#include "structure/structure.hpp"

namespace {

// STL covers both its ASCII and binary forms: assimp tells them by content.
constexpr const char* kExtensions[] = {"obj", "stl", "ply", "off", "gltf"};
constexpr std::size_t kExtensionCount = std::size(kExtensions);
constexpr double kWeldTolerances[] = {1e-9, 0.0, 1e-3};
constexpr std::size_t kWeldToleranceCount = std::size(kWeldTolerances);

const std::filesystem::path& scratch_folder() {
  static const ashlar::fuzz::ScratchFolder folder("ashlar-fuzz-mesh");
  return folder.path();
}

}  // namespace

// assimp's readers leak what they had built when they give up on a
// malformed file (e.g. its ASCII STL reader, assimp issue 5946, fixed after
// the 5.2.5 that Debian 12 ships): a few KB per bad file, not ours to fix.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t format = data[0] % kExtensionCount;
  ashlar::ImportOptions options;
  options.relative_weld_tolerance = kWeldTolerances[(data[0] / kExtensionCount) % kWeldToleranceCount];
  const std::filesystem::path path = scratch_folder() / (std::string("input.") + kExtensions[format]);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    ashlar::Structure structure;
    for (ashlar::ImportedBlock& imported : ashlar::import_blocks(path.string(), options)) {
      structure.add(std::make_shared<const ashlar::Block>(std::move(imported.block)), false,
                    imported.name);
    }
  } catch (const ashlar::Error&) {
  }
  return 0;
}
