// ashlar.gradient: the structural gradient of the equilibrium penalty.
#include "wrap_gradient.hpp"

#include "analysis/structural_gradient.hpp"
#include "analysis/interior_point.hpp"
#include "luax.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

void push_structural_gradient(lua_State* L, const StructuralGradient& gradient) {
  const EquilibriumResult& r = gradient.analysis;
  lua_createtable(L, static_cast<int>(gradient.block_vertices.size()), 9);
  for (size_t i = 0; i < gradient.block_vertices.size(); ++i) {
    push_points(L, gradient.block_vertices[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_createtable(L, static_cast<int>(gradient.cable_from.size()), 0);
  for (size_t c = 0; c < gradient.cable_from.size(); ++c) {
    lua_createtable(L, 0, 2);
    set_field(L, "from", gradient.cable_from[c]);
    set_field(L, "to", gradient.cable_to[c]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(c + 1));
  }
  lua_setfield(L, -2, "cables");
  set_field(L, "penalty", r.penalty);
  set_field(L, "infeasibility", r.infeasibility);
  set_boolean(L, "stable", r.stable);
  set_boolean(L, "valid", gradient.valid);
  set_string(L, "status", status_name(r.status));
  set_field(L, "seconds", gradient.seconds);
  set_field(L, "analysis_seconds", r.seconds);
}

namespace {

int w_gradient(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const AnalysisSettings settings =
        analysis_settings(OptionTable(L, 2, {ASHLAR_ANALYSIS_OPTIONS}));
    const StructuralGradient gradient = structural_gradient(s, settings);
    return call_protected(L, 0, [&](lua_State* L) {
      push_structural_gradient(L, gradient);
      return 1;
    });
  });
}

}  // namespace

void set_gradient_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"gradient", w_gradient}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
