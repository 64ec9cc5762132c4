// ashlar.weight_sensitivity, ashlar.load_capacity, ashlar.necessary_weights
// and ashlar.important_weights: per-block answers to how the blocks'
// weights hold a structure up.
#include "wrap_weights.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "analysis/load_capacity.hpp"
#include "analysis/weight_analysis.hpp"
#include "core/error.hpp"
#include "luax.hpp"
#include "progress_line.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

// The list t[i] = values[i] (i 1-based) into the table on top of the stack.
void set_list(lua_State* L, const std::vector<double>& values) {
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

// The options of the per-block analyses (load_capacity, important_weights)
// into their settings: `threads` (0 for one per core), `symmetry` (solve
// one block per orbit of the problem's symmetries) and `blocks` (the blocks
// asked, else every block).
template <class Settings>
Settings per_block_settings(lua_State* L, const Structure& s, const OptionTable& options) {
  Settings settings;
  settings.analysis = analysis_settings(options);
  settings.threads = static_cast<int>(
      options.whole("threads", 0, 1024, "a whole number from 0 (one per core) to 1024").value_or(settings.threads));
  settings.use_symmetry = options.boolean("symmetry").value_or(settings.use_symmetry);
  if (options.push("blocks") != LUA_TNIL) settings.blocks = check_block_list(L, s, -1, options.arg(), "blocks");
  lua_pop(L, 1);
  try {
    asked_blocks(s, settings.blocks, "");  // a block listed twice, named as an argument error
  } catch (const InvalidArgument& e) {
    throw ArgError(options.arg(), e.what());
  }
  return settings;
}

// What a per-block analysis works on, for its progress line: "1010 blocks",
// or "32 of 1010 blocks" asked.
std::string blocks_label(const Structure& s, const std::vector<int>& asked) {
  const std::string all = std::to_string(s.size()) + " blocks";
  return asked.empty() ? all : std::to_string(asked.size()) + " of " + all;
}

int w_weight_sensitivity(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const int block = check_block_index(L, s, 2, 2, "block");
    const AnalysisSettings settings = analysis_settings(OptionTable(L, 3, {ASHLAR_ANALYSIS_OPTIONS}));
    const WeightSensitivity sensitivity = weight_sensitivity(s, block, settings);
    const std::shared_ptr<const std::vector<Interface>> interfaces_list = s.interfaces(settings.problem.contact);
    const std::vector<Interface>& interfaces = *interfaces_list;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, s.size(), 6);
      set_list(L, sensitivity.block_change);
      lua_createtable(L, static_cast<int>(sensitivity.interface_change.size()), 0);
      for (size_t k = 0; k < sensitivity.interface_change.size(); ++k) {
        lua_createtable(L, 0, 4);
        set_index_field(L, "a", interfaces[k].a);
        set_index_field(L, "b", interfaces[k].b);
        set_field(L, "change", sensitivity.interface_change[k]);
        set_field(L, "resultant", sensitivity.interface_resultant_change[k]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "interfaces");
      set_boolean(L, "valid", sensitivity.valid);
      set_boolean(L, "stable", sensitivity.analysis.stable);
      set_string(L, "status", status_name(sensitivity.analysis.status));
      set_field(L, "seconds", sensitivity.seconds);
      set_field(L, "analysis_seconds", sensitivity.analysis.seconds);
      return 1;
    });
  });
}

int w_load_capacity(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {ASHLAR_ANALYSIS_OPTIONS, "threads", "progress", "symmetry", "blocks"});
    const LoadCapacitySettings settings = per_block_settings<LoadCapacitySettings>(L, s, options);
    ProgressLine line(options, "load_capacity", blocks_label(s, settings.blocks), "block");
    const LoadCapacity capacity = load_capacity(s, settings, line.callback());
    line.finish(kMarginStatusNames.name(capacity.status));
    const std::vector<char> asked = asked_blocks(s, settings.blocks, "load capacity");
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, s.size(), 5);
      for (int i = 0; i < s.size(); ++i) {
        if (!asked[i]) continue;  // nil: not asked
        if (std::isnan(capacity.max[i])) {
          lua_pushboolean(L, false);
        } else {
          lua_createtable(L, 0, 2);
          set_field(L, "min", capacity.min[i]);
          set_field(L, "max", capacity.max[i]);  // inf is math.huge
        }
        lua_rawseti(L, -2, i + 1);
      }
      set_boolean(L, "stable", capacity.stable);
      set_string(L, "status", kMarginStatusNames.name(capacity.status));
      set_field(L, "programs", capacity.programs);
      set_field(L, "symmetries", capacity.symmetries);
      set_field(L, "iterations", capacity.simplex_iterations);
      set_field(L, "seconds", capacity.seconds);
      return 1;
    });
  });
}

int w_necessary_weights(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const int block = check_block_index(L, s, 2, 2, "block");
    const AnalysisSettings settings = analysis_settings(OptionTable(L, 3, {ASHLAR_ANALYSIS_OPTIONS}));
    const NecessaryWeights needed = necessary_weights(s, block, settings);
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, s.size(), 5);
      set_list(L, needed.weights);
      set_boolean(L, "stable", needed.stable);
      set_field(L, "infeasibility", needed.infeasibility);
      set_string(L, "status", status_name(needed.status));
      set_field(L, "iterations", needed.iterations);
      set_field(L, "seconds", needed.seconds);
      return 1;
    });
  });
}

int w_important_weights(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {ASHLAR_ANALYSIS_OPTIONS, "threads", "progress", "symmetry", "blocks"});
    const ImportantWeightsSettings settings = per_block_settings<ImportantWeightsSettings>(L, s, options);
    ProgressLine line(options, "important_weights", blocks_label(s, settings.blocks), "block");
    const ImportantWeights important = important_weights(s, settings, line.callback());
    const char* status = kImportantWeightsStatusNames.name(important.status);
    line.finish(status);
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, s.size(), 7);
      set_list(L, important.per_volume);
      lua_createtable(L, static_cast<int>(important.unstable_blocks.size()), 0);
      for (size_t k = 0; k < important.unstable_blocks.size(); ++k) {
        lua_pushinteger(L, important.unstable_blocks[k] + 1);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "unstable");
      set_string(L, "status", status);
      set_field(L, "solves", important.solves);
      set_field(L, "iterations", important.iterations);
      set_field(L, "symmetries", important.symmetries);
      set_field(L, "seconds", important.seconds);
      return 1;
    });
  });
}

}  // namespace

void set_weights_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"weight_sensitivity", w_weight_sensitivity},
                                       {"load_capacity", w_load_capacity},
                                       {"necessary_weights", w_necessary_weights},
                                       {"important_weights", w_important_weights},
                                       {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
