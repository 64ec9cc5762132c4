// Lua type "ashlar.Result": the outcome of ashlar.analyze. Its fields
// (stable, infeasibility, interfaces, ...) are computed on access.
#pragma once

#include <lua.hpp>

#include <array>
#include <functional>
#include <vector>

#include "analysis/equilibrium.hpp"

namespace ashlar::lua {

class OptionTable;

// The option names of ashlar.analyze, for option tables that accept them.
#define ASHLAR_ANALYSIS_OPTIONS                                                          \
  "friction", "friction_sides", "friction_model", "tension_weight", "force_weight",      \
      "tolerance", "max_iterations", "stable_tolerance", "contact_tolerance", "contact_angle",     \
      "contact_min_width", "contact_min_area"
// The `friction` option: a number >= 0, math.huge for no sliding;
// `fallback` when absent.
double friction_option(const OptionTable& options, double fallback);
// Analysis settings from an option table that allows ASHLAR_ANALYSIS_OPTIONS.
AnalysisSettings analysis_settings(const OptionTable& options);

// The engine result held by the Result at idx, for the caller to keep while
// it uses it (see check_boxed), or nullptr if it is not an open Result.
std::shared_ptr<const EquilibriumResult> luax_testResult(lua_State* L, int idx);
// The `result` option of `options` (nil: none), for the caller to keep while
// it uses it; an error unless it is an open Result.
std::shared_ptr<const EquilibriumResult> result_option(lua_State* L, const OptionTable& options);
void register_Result(lua_State* L);
// A new Result of `structure` holding `result`.
void luax_pushResult(lua_State* L, const Structure& structure, EquilibriumResult result);
// The "method" option ("equilibrium", "kinematic", "cra", "cra_penalty")
// into settings. With a `caller` (a function that offers only the first
// two), "cra" and "cra_penalty" are errors naming the caller.
void read_method(const OptionTable& options, AnalysisSettings& settings, const char* caller = nullptr);

// The relative width of a search's final bracket (load_factor and
// friction_demand with method = "kinematic", friction_demand,
// geometric_factor): option `bracket_tolerance`, or `tolerance`, its older
// name in these functions (an error when both are given); a number in
// (0, 1), `fallback` when neither is given. Errors name the key given.
double bracket_tolerance(const OptionTable& options, double fallback);

// A collapse mechanism as Lua tables (ashlar.analyze's and
// ashlar.load_factor's): per block { velocity, rotation }, and the moving
// interfaces { interface, a, b, mode, pivot, opening, slip }, their blocks
// from ends_of(interface index) -> {a, b} (0-based).
void push_mechanism(lua_State* L, const std::vector<BlockMotion>& mechanism);
void push_limit(lua_State* L, const std::vector<LimitInterface>& limit,
                const std::function<std::array<int, 2>(int)>& ends_of);
// ashlar.analyze and ashlar.export_qp: set into the table on top of the stack.
void set_analysis_functions(lua_State* L);

}  // namespace ashlar::lua
