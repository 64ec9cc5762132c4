// The interactive HTML viewer: ashlar.export to a .html file.
//
// One self-contained page that opens offline in any browser with WebGL:
// web/viewer.html with the scene (the objects of structure_scene.hpp, the
// very ones the mesh files hold, as JSON) and every script inlined: the
// viewer (web/viewer.js) and three.js with its OrbitControls, embedded in
// the engine at build time from web/node_modules (web_assets.hpp). The page
// turns and zooms, draws block outlines, colours blocks with a legend when
// options.color_scale says what the colours mean, shows the name and values
// of the block, arrow or interface under the pointer, and switches each
// layer (blocks, edges, interfaces, forces, thrust, cables, traces) on and
// off.
#pragma once

#include <string>

#include "io/mesh_io.hpp"

namespace ashlar {

// Writes the page to `path` atomically, whatever its extension. Checks the
// options as export_structure does (InvalidArgument); IoError on failure.
void write_viewer_page(const Structure& structure, const std::string& path, const ExportOptions& options);

}  // namespace ashlar
