// Fuzz target: the structure file reader (structure_from_json), as
// ashlar.load uses it. Bad text must give an ashlar::IoError or another
// ashlar::Error naming what was wrong; any other exception escapes and counts
// as a crash. A structure that loads must save, and load back to the same
// text: that is what keeps saved files stable.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.hpp"
#include "io/structure_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ashlar::Structure structure;
  try {
    structure = ashlar::structure_from_json(text, "fuzz input");
  } catch (const ashlar::Error&) {
    return 0;
  }
  const std::string saved = ashlar::structure_to_json(structure);
  const std::string saved_again =
      ashlar::structure_to_json(ashlar::structure_from_json(saved, "saved fuzz input"));
  if (saved_again != saved) {
    std::fprintf(stderr, "save/load/save changed the file:\n%s\n---\n%s\n", saved.c_str(),
                 saved_again.c_str());
    std::abort();
  }
  return 0;
}
