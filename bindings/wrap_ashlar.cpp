// The `ashlar` library table: version, constructors, files.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "ashlar_lua.hpp"
#include "core/error.hpp"
#include "core/process_stats.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "io/color_map.hpp"
#include "io/compas_assembly.hpp"
#include "io/mesh_io.hpp"
#include "io/viewer_page.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_Block.hpp"
#include "wrap_Result.hpp"
#include "wrap_Simulation.hpp"
#include "wrap_Structure.hpp"
#include "wrap_chart.hpp"
#include "wrap_colors.hpp"
#include "wrap_draw.hpp"
#include "wrap_export.hpp"
#include "wrap_fea.hpp"
#include "wrap_force_flow.hpp"
#include "wrap_gradient.hpp"
#include "wrap_margins.hpp"
#include "wrap_optimize.hpp"
#include "wrap_search.hpp"
#include "wrap_study.hpp"
#include "wrap_sandbox.hpp"
#include "wrap_weights.hpp"

namespace ashlar::lua {

namespace {


// `traces` export option: the table ashlar.trace_loads returned (its
// polylines are drawn).
std::vector<std::vector<Vec3>> load_traces(lua_State* L, const OptionTable& options) {
  const int arg = options.arg();
  std::vector<std::vector<Vec3>> traces;
  if (options.push("traces") == LUA_TNIL) {
    lua_pop(L, 1);
    return traces;
  }
  if (lua_type(L, -1) != LUA_TTABLE || get_field(L, -1, "polylines") != LUA_TTABLE) {
    throw ArgError(arg, "traces: expected the table ashlar.trace_loads returned (with polylines)");
  }
  const lua_Unsigned count = lua_rawlen(L, -1);
  for (lua_Unsigned k = 1; k <= count; ++k) {
    lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
    traces.push_back(to_points(L, -1, arg, "traces.polylines[" + std::to_string(k) + "]"));
    lua_pop(L, 1);
  }
  lua_pop(L, 2);
  return traces;
}

}  // namespace

ExportOptions block_appearance(lua_State* L, const OptionTable& options, int blocks, bool html) {
  ExportOptions exported;
  BlockColoring coloring = block_coloring(L, options, blocks);
  exported.block_colors = std::move(coloring.colors);
  if (html) exported.color_scale = std::move(coloring.scale);
  if (const std::optional<std::string> legend = options.string("legend")) {
    if (!exported.color_scale) {
      throw ArgError(options.arg(), "legend: \"" + *legend + "\" labels colours mapped from values; give "
                                    "color = { values = {...}, map = ..., range = ... } with it");
    }
    exported.color_scale->label = *legend;
  }
  exported.title = options.string("title").value_or("");
  // The viewer's outlines are lines, shown unless edges = false.
  exported.edges = options.boolean("edges").value_or(html);
  if (const std::optional<double> opacity = options.number("opacity")) {
    if (!(*opacity >= 0.0 && *opacity <= 1.0)) {
      throw ArgError(options.arg(), "opacity: expected a number in [0, 1], got " + number_text(*opacity));
    }
    exported.block_opacity = opacity;
  }
  return exported;
}

void export_with_options(lua_State* L, const Structure& s, const std::string& path, const OptionTable& options) {
  const std::optional<std::string> format = options.string("format");
  if (format && *format != "compas" && *format != "html") {
    throw ArgError(options.arg(), "format: expected \"compas\" or \"html\" (other formats follow the file's "
                                  "extension), got \"" + *format + "\"");
  }
  if (format == "compas" || (!format && file_extension(path) == "json")) {
    CompasExportOptions compas;
    compas.contact.tolerance = options.positive("tolerance", 0.0, true);
    const std::shared_ptr<const EquilibriumResult> result = result_option(L, options);
    compas.result = result.get();
    for (const char* key : {"color", "interfaces", "forces", "thrust", "force_scale", "opacity", "cable_color",
                            "traces", "trace_color", "mechanism", "edges", "title", "legend", "limit", "autoplay"}) {
      if (options.has(key)) {
        throw ArgError(options.arg(), std::string(key) + ": does not apply to a COMPAS assembly (.json), which "
                                                         "holds blocks, supports, interfaces and, with result, "
                                                         "their forces");
      }
    }
    write_compas_assembly(s, path, compas);
    return;
  }
  const bool html = format == "html" || (!format && file_extension(path) == "html");
  if (!html) {
    for (const char* key : {"title", "legend"}) {
      if (const std::optional<std::string> text = options.string(key)) {
        throw ArgError(options.arg(), std::string(key) + ": only the HTML viewer (a .html path, or format = "
                                                         "\"html\") has one, got \"" + *text + "\" for '" + path + "'");
      }
    }
  }
  ExportOptions exported = block_appearance(L, options, s.size(), html);
  exported.interfaces = options.boolean("interfaces").value_or(false);
  exported.contact.tolerance = options.positive("tolerance", 0.0, true);
  const ResultOption result = result_with_mechanism(L, options, s, exported.contact);
  exported.result = result.analysis.get();
  exported.mechanism = result.mechanism();
  if (result.factor) exported.load_factor = result.factor->factor;
  if (options.boolean("limit").value_or(result.factor.has_value())) exported.limit = result.limit();
  // forces = true draws the resultants; a ForceMode's name chooses.
  if (options.push("forces") == LUA_TSTRING) {
    exported.forces = true;
    exported.force_mode = *options.choice("forces", kForceModeNames);
  } else if (lua_type(L, -1) != LUA_TNIL && lua_type(L, -1) != LUA_TBOOLEAN) {
    throw ArgError(options.arg(), "forces: expected true, false or one of " + kForceModeNames.list() + ", got " +
                                      type_name(L, -1));
  } else {
    exported.forces = lua_toboolean(L, -1);
  }
  lua_pop(L, 1);
  // A load factor's result is drawn for its limit state: the thrust line at the factor.
  exported.thrust = options.boolean("thrust").value_or(result.factor.has_value());
  exported.force_scale = options.positive("force_scale", 0.0, true);
  // mechanism = false: the HTML page is a still, with the blocks where they stand.
  if (options.push("mechanism") == LUA_TBOOLEAN) {
    if (lua_toboolean(L, -1)) {
      throw ArgError(options.arg(), "mechanism: expected a distance >= 0 (m) or false, got true");
    }
    exported.animate_mechanism = false;
  } else {
    exported.mechanism_scale = options.positive("mechanism", 0.0, true);
  }
  lua_pop(L, 1);
  if (const std::optional<bool> autoplay = options.boolean("autoplay")) {
    const bool has_mechanism = exported.mechanism || (exported.result && !exported.result->mechanism.empty());
    if (!(html && exported.animate_mechanism && has_mechanism)) {
      throw ArgError(options.arg(), "autoplay: applies to a page (.html) that plays a collapse mechanism (a result "
                                    "with one: a load factor's, an unstable analysis's), got " +
                                        std::string(*autoplay ? "true" : "false"));
    }
    exported.autoplay = *autoplay;
  }
  if (options.push("cable_color") != LUA_TNIL) {
    exported.cable_color = to_rgb(L, -1, options.arg(), "cable_color");
  }
  lua_pop(L, 1);
  exported.traces = load_traces(L, options);
  if (options.push("trace_color") != LUA_TNIL) {
    exported.trace_color = to_rgb(L, -1, options.arg(), "trace_color");
  }
  lua_pop(L, 1);
  if (html) {
    write_viewer_page(s, path, exported);
  } else {
    export_structure(s, path, exported);
  }
}

namespace {

int w_export(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    export_with_options(L, *structure, path, OptionTable(L, 3, {ASHLAR_EXPORT_OPTIONS}));
    return 0;
  });
}

// Decides whether an imported block is a support: `support` is a Lua pattern
// matched against the name, or a function(name, block) returning a boolean.
bool is_support(lua_State* L, int rule, const ImportedBlock& imported) {
  switch (lua_type(L, rule)) {
    case LUA_TNIL:
      return false;
    case LUA_TSTRING:
      return matches_pattern(L, imported.name.c_str(), lua_tostring(L, rule));
    case LUA_TFUNCTION: {
      lua_pushvalue(L, rule);
      push_string(L, imported.name);
      luax_pushBlock(L, std::make_shared<const Block>(imported.block));
      protected_call(L, 2, 1);
      const bool chosen = lua_toboolean(L, -1);
      lua_pop(L, 1);
      return chosen;
    }
    default:
      throw ArgError(2, "support: expected a name pattern (string) or function(name, block), got " +
                            type_name(L, rule));
  }
}

int w_import(lua_State* L) {
  return guard(L, [&] {
    const std::string path = sandbox::checked_path(L, 1, "path", sandbox::Access::read);
    const OptionTable options(L, 2, {"support", "density", "planarity", "interfaces"});
    ImportOptions import_options;
    import_options.density = options.positive("density", kDefaultDensity);
    import_options.planarity = options.positive("planarity", 0.0, /*zero_allowed=*/true);
    if (sandbox::settings_of(L) != nullptr)
      import_options.may_open = [L](const std::string& file) {
        return sandbox::access_problem(L, file, sandbox::Access::read).empty();
      };
    options.push("support");
    const int rule = lua_gettop(L);
    if (!lua_isnil(L, rule) && lua_type(L, rule) != LUA_TSTRING && !lua_isfunction(L, rule)) {
      throw ArgError(2, "support: expected a name pattern (string) or function(name, block), got " +
                            type_name(L, rule));
    }
    const bool compas = file_extension(path) == "json";
    const std::optional<std::string> interfaces = options.string("interfaces");
    if (interfaces && !compas) {
      throw ArgError(2, "interfaces: applies to COMPAS assembly files (.json) only, not to '" + path + "'");
    }
    if (interfaces && *interfaces != "file" && *interfaces != "detect") {
      throw ArgError(2, "interfaces: expected \"file\" (the file's stored interfaces, explicit) or \"detect\" "
                        "(found from the geometry), got \"" + *interfaces + "\"");
    }
    auto structure = std::make_shared<Structure>();
    if (compas) {
      *structure = compas_structure(read_compas_assembly(path, import_options), interfaces.value_or("file") == "file",
                                    [&](const ImportedBlock& imported) { return is_support(L, rule, imported); });
    } else {
      for (ImportedBlock& imported : import_blocks(path, import_options)) {
        const bool support = !imported.surface.empty() || is_support(L, rule, imported);
        structure->add(std::make_shared<const Block>(std::move(imported.block)), support,
                       imported.name);
      }
    }
    lua_pop(L, 1);
    luax_pushStructure(L, std::move(structure));
    return 1;
  });
}

// __index of a strict table (upvalue 1: its name for messages): reading a
// name it does not have is an error naming it and the nearest it has.
int strict_index(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;  // only names are checked
  return guard(L, [&]() -> int {
    std::vector<std::string> names;
    lua_pushnil(L);
    while (lua_next(L, 1)) {
      if (lua_type(L, -2) == LUA_TSTRING) names.emplace_back(lua_tostring(L, -2));
      lua_pop(L, 1);
    }
    const std::string key = lua_tostring(L, 2);
    const std::string nearest = closest_name(key, names);
    throw Error(std::string(lua_tostring(L, lua_upvalueindex(1))) + " has no function '" + key + "'" +
                (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
  });
}

// Makes table t (at idx) strict under `name`.
void make_strict(lua_State* L, int idx, const char* name) {
  idx = lua_absindex(L, idx);
  lua_createtable(L, 0, 1);
  lua_pushstring(L, name);
  lua_pushcclosure(L, strict_index, 1);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, idx);
}

// ashlar.strict(t, name): reading a name t does not have raises "name has
// no function 'x' (did you mean 'y'?)"; returns t.
int w_strict(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const char* name = luaL_checkstring(L, 2);
  if (lua_getmetatable(L, 1)) return luaL_argerror(L, 1, "the table already has a metatable");
  make_strict(L, 1, name);
  lua_settop(L, 1);
  return 1;
}

int w_clock(lua_State* L) {
  lua_pushnumber(L, monotonic_seconds());
  return 1;
}

int w_memory(lua_State* L) {
  return guard(L, [&] {
    const OptionTable options(L, 1, {"reset_peak"});
    if (options.boolean("reset_peak").value_or(false)) reset_peak_memory();
    const MemoryUse use = memory_use();
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 2);
      lua_pushnumber(L, use.resident_mb);
      lua_setfield(L, -2, "resident_mb");
      lua_pushnumber(L, use.peak_mb);
      lua_setfield(L, -2, "peak_mb");
      return 1;
    });
  });
}

}  // namespace

}  // namespace ashlar::lua

int ashlar_open_library(lua_State* L) {
  using namespace ashlar::lua;
  register_Block(L);
  register_Structure(L);
  register_Result(L);
  register_FeaResult(L);
  register_Study(L);
  register_Simulation(L);
  lua_newtable(L);
  lua_pushstring(L, ashlar::version());
  lua_setfield(L, -2, "version");
  set_block_constructors(L);
  set_structure_functions(L);
  set_analysis_functions(L);
  set_simulation_functions(L);
  set_gradient_functions(L);
  set_optimize_functions(L);
  set_weights_functions(L);
  set_force_flow_functions(L);
  set_draw_functions(L);
  set_chart_functions(L);
  set_fea_functions(L);
  set_margin_functions(L);
  set_search_functions(L);
  set_study_functions(L);
  set_sandbox_functions(L);
  static const luaL_Reg functions[] = {{"import", w_import}, {"export", w_export},
                                       {"clock", w_clock},   {"memory", w_memory},
                                       {"strict", w_strict}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
  make_strict(L, -1, "ashlar");  // ashlar.analyse: "did you mean 'analyze'?"
  return 1;
}

// With Lua strings only: it runs while a sandboxed state is made, and may
// run out of memory at any call.
void ashlar_add_model_path(lua_State* L) {
  const char* env = std::getenv("ASHLAR_MODELS");
  const char* folder = env && *env ? env : ASHLAR_MODELS_DIR;
  lua_getglobal(L, "package");
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    return;
  }
  const char* entries = lua_pushfstring(L, "%s/?.lua;%s/?/init.lua", folder, folder);
  lua_getfield(L, -2, "path");
  const char* path = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
  if (std::strstr(path, entries) == nullptr) {
    if (*path == '\0') lua_pushstring(L, entries);
    else lua_pushfstring(L, "%s;%s", path, entries);
    lua_setfield(L, -4, "path");
  }
  lua_pop(L, 3);
}
