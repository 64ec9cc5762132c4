// Files embedded in the engine at build time (web_assets.cpp): the HTML
// viewer's page and script from web/, and the three.js modules that npm
// installed in web/node_modules (pinned by web/package-lock.json). The
// program carries them, so pages are written the same from the build tree,
// an installed program or the Lua C module, and nothing is read or fetched
// when a page is written or opened.
#pragma once

#include <string_view>

namespace ashlar {

enum class WebAsset {
  viewer_page,     // web/viewer.html, with @TITLE@, @VERSION@, @SCENE@, @MODULES@ to fill in
  viewer_script,   // web/viewer.js, an ES module importing "three" and its OrbitControls
  three_core,      // three/build/three.core.min.js
  three_module,    // three/build/three.module.min.js (imports ./three.core.min.js)
  orbit_controls,  // three/examples/jsm/controls/OrbitControls.js (imports "three")
};

std::string_view web_asset(WebAsset asset);

}  // namespace ashlar
