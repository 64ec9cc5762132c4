// ashlar.gradient: d(penalty)/d(vertex and cable end positions).
#pragma once

#include <lua.hpp>

#include "analysis/structural_gradient.hpp"

namespace ashlar::lua {

// Pushes g: g[i][k] = {dx, dy, dz} for vertex k of block i, g.cables[c] =
// {from = {..}, to = {..}}, and penalty, infeasibility, stable, valid,
// status, seconds (the gradient's own time) and analysis_seconds.
void push_structural_gradient(lua_State* L, const StructuralGradient& gradient);
// ashlar.gradient: set into the table on top of the stack.
void set_gradient_functions(lua_State* L);

}  // namespace ashlar::lua
