// ashlar.export's options for 3D files, the HTML viewer and COMPAS assemblies, shared by
// every function that writes a structure the way ashlar.export does.
#pragma once

#include <lua.hpp>

#include <string>

#include "io/mesh_io.hpp"
#include "luax.hpp"
#include "structure/structure.hpp"

namespace ashlar::lua {

// The option names of ashlar.export.
#define ASHLAR_EXPORT_OPTIONS                                                                          \
  "format", "color", "interfaces", "tolerance", "result", "forces", "thrust", "force_scale", "opacity", \
      "cable_color", "traces", "trace_color", "mechanism", "edges", "title", "legend", "limit", "autoplay"

// The options that say how the blocks look, read from `options` as
// ashlar.export reads them: color (with legend and the colour scale only
// for the HTML viewer, `html`), title, edges (default: html) and opacity.
ExportOptions block_appearance(lua_State* L, const OptionTable& options, int blocks, bool html);

// Writes `s` to `path` as ashlar.export does with `options` (a table that
// allows ASHLAR_EXPORT_OPTIONS and maybe more keys, which are not read).
void export_with_options(lua_State* L, const Structure& s, const std::string& path, const OptionTable& options);

}  // namespace ashlar::lua
