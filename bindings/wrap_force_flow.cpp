// ashlar.trace_loads: the load traces of one block's weight.
#include "wrap_force_flow.hpp"

#include <climits>
#include <string>

#include "analysis/force_flow.hpp"
#include "luax.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

// Integer option `key`, at least `least` (and an int); `fallback` when absent.
int integer_option(const OptionTable& options, const char* key, int fallback, int least) {
  const std::optional<lua_Integer> value =
      options.whole(key, least, INT_MAX,
                    "an integer from " + std::to_string(least) + " to " + std::to_string(INT_MAX));
  return value ? static_cast<int>(*value) : fallback;
}

ForceFlowOptions flow_options(const OptionTable& options) {
  ForceFlowOptions flow;
  flow.traces = integer_option(options, "traces", flow.traces, 1);
  flow.seed = static_cast<std::uint64_t>(
      integer_option(options, "seed", static_cast<int>(flow.seed), 0));
  flow.start = options.choice("start", kTraceStartNames).value_or(flow.start);
  flow.max_steps = integer_option(options, "max_steps", flow.max_steps, 1);
  flow.turn_back = options.boolean("turn_back").value_or(flow.turn_back);
  return flow;
}

void push_force_flow(lua_State* L, const ForceFlow& flow) {
  lua_createtable(L, 0, 8);
  lua_createtable(L, static_cast<int>(flow.polylines.size()), 0);
  for (size_t t = 0; t < flow.polylines.size(); ++t) {
    push_points(L, flow.polylines[t]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(t + 1));
  }
  lua_setfield(L, -2, "polylines");
  lua_createtable(L, static_cast<int>(flow.support_interface.size()), 0);
  for (size_t t = 0; t < flow.support_interface.size(); ++t) {
    const int reached = flow.support_interface[t];
    if (reached >= 0) lua_pushinteger(L, reached + 1);
    else lua_pushboolean(L, false);
    lua_rawseti(L, -2, static_cast<lua_Integer>(t + 1));
  }
  lua_setfield(L, -2, "support");
  lua_createtable(L, static_cast<int>(flow.shares.size()), 0);
  for (size_t k = 0; k < flow.shares.size(); ++k) {
    const SupportShare& share = flow.shares[k];
    lua_createtable(L, 0, 4);
    set_index_field(L, "interface", share.interface);
    set_index_field(L, "a", share.a);
    set_index_field(L, "b", share.b);
    set_field(L, "share", share.share);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "shares");
  lua_pushinteger(L, flow.lost);
  lua_setfield(L, -2, "lost");
  set_boolean(L, "stable", flow.stable);
  set_boolean(L, "valid", flow.valid);
  set_string(L, "status", status_name(flow.analysis.status));
  set_field(L, "seconds", flow.seconds);
}

int w_trace_loads(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const int block = check_block_index(L, s, 2, 2, "block");
    const OptionTable options(L, 3, {ASHLAR_ANALYSIS_OPTIONS, "traces", "seed", "start",
                                     "max_steps", "turn_back"});
    const AnalysisSettings settings = analysis_settings(options);
    const ForceFlow flow = trace_loads(s, block, flow_options(options), settings);
    return call_protected(L, 0, [&](lua_State* L) {
      push_force_flow(L, flow);
      return 1;
    });
  });
}

}  // namespace

void set_force_flow_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"trace_loads", w_trace_loads}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
