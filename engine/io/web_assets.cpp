// The assets of web_assets.hpp, assembled into read-only data with
// .incbin: the files are taken as they are, without a conversion step.
// ASHLAR_WEB_DIR and ASHLAR_THREE_DIR come from engine/io/CMakeLists.txt,
// which also rebuilds this file when an asset changes.
#include "io/web_assets.hpp"

// Defines the hidden symbols ashlar_asset_<name> and ashlar_asset_<name>_end
// around the file's bytes.
#define ASHLAR_EMBED(name, file)                  \
  __asm__(".pushsection .rodata\n"                \
          ".global ashlar_asset_" #name "\n"      \
          ".hidden ashlar_asset_" #name "\n"      \
          "ashlar_asset_" #name ":\n"             \
          ".incbin \"" file "\"\n"                \
          ".global ashlar_asset_" #name "_end\n"  \
          ".hidden ashlar_asset_" #name "_end\n"  \
          "ashlar_asset_" #name "_end:\n"         \
          ".popsection\n");                       \
  extern "C" const char ashlar_asset_##name[];    \
  extern "C" const char ashlar_asset_##name##_end[];

ASHLAR_EMBED(viewer_page, ASHLAR_WEB_DIR "/viewer.html")
ASHLAR_EMBED(viewer_script, ASHLAR_WEB_DIR "/viewer.js")
ASHLAR_EMBED(three_core, ASHLAR_THREE_DIR "/build/three.core.min.js")
ASHLAR_EMBED(three_module, ASHLAR_THREE_DIR "/build/three.module.min.js")
ASHLAR_EMBED(orbit_controls, ASHLAR_THREE_DIR "/examples/jsm/controls/OrbitControls.js")

namespace ashlar {
namespace {

std::string_view between(const char* begin, const char* end) {
  return std::string_view(begin, static_cast<std::size_t>(end - begin));
}

}  // namespace

std::string_view web_asset(WebAsset asset) {
  switch (asset) {
    case WebAsset::viewer_page: return between(ashlar_asset_viewer_page, ashlar_asset_viewer_page_end);
    case WebAsset::viewer_script: return between(ashlar_asset_viewer_script, ashlar_asset_viewer_script_end);
    case WebAsset::three_core: return between(ashlar_asset_three_core, ashlar_asset_three_core_end);
    case WebAsset::three_module: return between(ashlar_asset_three_module, ashlar_asset_three_module_end);
    case WebAsset::orbit_controls: return between(ashlar_asset_orbit_controls, ashlar_asset_orbit_controls_end);
  }
  return {};
}

}  // namespace ashlar
