#include "wrap_margins.hpp"

#include "analysis/kinematic.hpp"
#include "analysis/load_factor.hpp"
#include "luax.hpp"
#include "progress_line.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

// The options that shape the program (friction and contacts, as the
// analysis finds them); the interior point solver's do not apply.
#define ASHLAR_PROGRAM_OPTIONS \
  "friction_sides", "friction_model", "contact_tolerance", "contact_angle", "contact_min_width", "contact_min_area"

int w_load_factor(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2,
                              {"friction", ASHLAR_PROGRAM_OPTIONS, "direction", "load", "method", "bracket_tolerance",
                               "tolerance", "progress"});
    AnalysisSettings analysis = analysis_settings(options);
    analysis.solver = InteriorPointSettings{};  // "tolerance" is the bracket's here (bracket_tolerance), as for friction_demand
    read_method(options, analysis, "load_factor");
    LoadFactorSettings settings;
    settings.problem = analysis.problem;
    settings.pattern = options.choice("load", kLoadPatternNames).value_or(settings.pattern);
    if (const std::optional<Vec3> direction = options.vec3("direction")) {
      if (settings.pattern == LoadPattern::point_loads) {
        throw ArgError(2, "direction: not with load = 'point_loads' (the loads have their own)");
      }
      settings.direction = *direction;
    }
    if (analysis.method == AnalysisMethod::kinematic) {
      KinematicLoadFactorSettings kinematic;
      kinematic.load = settings;
      kinematic.analysis = analysis;
      kinematic.bracket_tolerance = bracket_tolerance(options, kinematic.bracket_tolerance);
      // A bisection of kinematic analyses: a line of its bracket's digits once it has taken 2 s.
      ProgressLine line(options, "load_factor", std::to_string(s.size()) + " blocks", "digit", 2.0);
      const KinematicLoadFactor factor = kinematic_load_factor(s, kinematic, line.callback());
      line.finish(kMarginStatusNames.name(factor.status));
      const EquilibriumResult& failure = factor.failure;
      const std::function<std::array<int, 2>(int)> ends_of = [&](int k) {
        return std::array<int, 2>{failure.interfaces[k].a, failure.interfaces[k].b};
      };
      return call_protected(L, 0, [&](lua_State* L) {
        lua_createtable(L, 0, 8);
        set_string(L, "method", kAnalysisMethodNames.name(AnalysisMethod::kinematic));
        set_field(L, "factor", factor.factor);
        set_string(L, "status", kMarginStatusNames.name(factor.status));
        set_boolean(L, "stable", factor.stable);
        set_field(L, "equilibrium_factor", factor.equilibrium_factor);
        lua_pushinteger(L, factor.analyses);
        lua_setfield(L, -2, "analyses");
        set_field(L, "seconds", factor.seconds);
        if (!failure.mechanism.empty()) {
          push_mechanism(L, failure.mechanism);
          lua_setfield(L, -2, "mechanism");
          push_limit(L, failure.limit, ends_of);
          lua_setfield(L, -2, "limit");
        }
        return 1;
      });
    }
    for (const char* key : {"bracket_tolerance", "tolerance"}) {
      if (options.has(key)) throw ArgError(2, std::string(key) + ": only with method = \"kinematic\" (a bisection)");
    }
    // A line of Clp's iterations once the program has taken 2 s (a
    // 1,008-voussoir vault's takes 15 s and more); most answer sooner.
    ProgressLine line(options, "load_factor", std::to_string(s.size()) + " blocks", "iteration", 2.0);
    const LoadFactor factor = load_factor(s, settings, line.callback());
    line.finish(kMarginStatusNames.name(factor.status));
    const std::shared_ptr<const std::vector<Interface>> interfaces_list = s.interfaces(settings.problem.contact);
    const std::vector<Interface>& interfaces = *interfaces_list;
    const std::function<std::array<int, 2>(int)> ends_of = [&](int k) {
      return std::array<int, 2>{interfaces[k].a, interfaces[k].b};
    };
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 8);
      set_field(L, "factor", factor.factor);
      set_string(L, "status", kMarginStatusNames.name(factor.status));
      set_boolean(L, "stable", factor.stable);
      set_field(L, "iterations", factor.iterations);
      set_field(L, "seconds", factor.seconds);
      // What ashlar.draw and ashlar.export need to analyse it at its factor.
      set_string(L, "load", kLoadPatternNames.name(settings.pattern));
      if (settings.pattern == LoadPattern::body_force) set_field(L, "direction", Vec3(settings.direction.normalized()));
      set_field(L, "friction", settings.problem.friction);
      push_limit(L, factor.limit, ends_of);
      lua_setfield(L, -2, "limit");
      if (!factor.mechanism.empty()) {
        push_mechanism(L, factor.mechanism);
        lua_setfield(L, -2, "mechanism");
      }
      return 1;
    });
  });
}

int w_friction_demand(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {ASHLAR_PROGRAM_OPTIONS, "bracket_tolerance", "tolerance", "method", "progress"});
    AnalysisSettings analysis = analysis_settings(options);
    analysis.solver = InteriorPointSettings{};  // "tolerance" is the bracket's (bracket_tolerance)
    read_method(options, analysis, "friction_demand");
    const EquilibriumOptions& problem = analysis.problem;
    const bool kinematic = analysis.method == AnalysisMethod::kinematic;
    KinematicFrictionDemandSettings kinematic_settings;
    kinematic_settings.analysis = analysis;
    FrictionDemandSettings settings;
    settings.problem = problem;
    double& tolerance = kinematic ? kinematic_settings.bracket_tolerance : settings.bracket_tolerance;
    tolerance = bracket_tolerance(options, tolerance);
    // A line once the search has taken 2 s: most answer sooner.
    ProgressLine line(options, "friction_demand", std::to_string(s.size()) + " blocks", "digit", 2.0);
    const FrictionDemand demand = kinematic ? kinematic_friction_demand(s, kinematic_settings, line.callback())
                                            : friction_demand(s, settings, line.callback());
    line.finish(kMarginStatusNames.name(demand.status));
    const std::shared_ptr<const std::vector<Interface>> interfaces_list = s.interfaces(problem.contact);
    const std::vector<Interface>& interfaces = *interfaces_list;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 8);
      set_string(L, "method", kAnalysisMethodNames.name(analysis.method));
      set_field(L, "friction", demand.friction);
      set_field(L, "lower", demand.lower);
      set_string(L, "status", kMarginStatusNames.name(demand.status));
      set_field(L, "programs", demand.programs);
      set_field(L, "iterations", demand.iterations);
      set_field(L, "seconds", demand.seconds);
      lua_createtable(L, static_cast<int>(demand.critical.size()), 0);
      for (size_t k = 0; k < demand.critical.size(); ++k) {
        const Interface& contact = interfaces[demand.critical[k]];
        lua_createtable(L, 0, 3);
        set_field(L, "interface", demand.critical[k] + 1);
        set_index_field(L, "a", contact.a);
        set_index_field(L, "b", contact.b);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "critical");
      return 1;
    });
  });
}

}  // namespace

std::optional<LoadFactorRecord> to_load_factor(lua_State* L, int idx, int arg, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE) return std::nullopt;
  const bool factor = get_field(L, idx, "factor") == LUA_TNUMBER;
  const bool load = get_field(L, idx, "load") == LUA_TSTRING;
  const bool kinematic = get_field(L, idx, "method") == LUA_TSTRING &&
                         lua_tostring(L, -1) == std::string(kAnalysisMethodNames.name(AnalysisMethod::kinematic));
  lua_pop(L, 3);
  if (factor && kinematic) {
    throw ArgError(arg, what + ": a load factor of the kinematic method has no equilibrium at its factor (its "
                               "mechanism is the analysis's just above it): give that analysis's Result");
  }
  if (!factor || !load) return std::nullopt;
  LoadFactorRecord record;
  get_field(L, idx, "factor");
  record.factor = check_number(L, -1, arg, (what + ".factor (a load factor that has no finite factor has no limit state to draw)").c_str());
  lua_pop(L, 1);
  get_field(L, idx, "load");
  const std::string pattern = lua_tostring(L, -1);
  lua_pop(L, 1);
  const std::optional<LoadPattern> parsed = kLoadPatternNames.parse(pattern);
  if (!parsed) throw ArgError(arg, what + ".load: expected " + kLoadPatternNames.list() + ", got '" + pattern + "'");
  record.settings.pattern = *parsed;
  if (record.settings.pattern == LoadPattern::body_force) {
    if (get_field(L, idx, "direction") != LUA_TTABLE) {
      throw ArgError(arg, what + ".direction: expected {x, y, z} (the load factor's), got " + type_name(L, -1));
    }
    record.settings.direction = to_vec3(L, -1, arg, what + ".direction");
    lua_pop(L, 1);
  }
  if (get_field(L, idx, "friction") != LUA_TNUMBER || !(lua_tonumber(L, -1) >= 0.0)) {
    throw ArgError(arg, what + ".friction: expected a number >= 0 (the load factor's), got " +
                            (lua_type(L, -1) == LUA_TNUMBER ? lua_number_text(L, -1) : type_name(L, -1)));
  }
  record.settings.problem.friction = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (get_field(L, idx, "mechanism") != LUA_TTABLE) {
    throw ArgError(arg, what + ".mechanism: expected the list of block motions, got " + type_name(L, -1));
  }
  const lua_Integer blocks = luaL_len(L, -1);
  for (lua_Integer i = 1; i <= blocks; ++i) {
    lua_rawgeti(L, -1, i);
    const std::string name = what + ".mechanism[" + std::to_string(i) + "]";
    if (!lua_istable(L, -1)) throw ArgError(arg, name + ": expected { velocity, rotation }, got " + type_name(L, -1));
    BlockMotion motion;
    get_field(L, -1, "velocity");
    motion.velocity = to_vec3(L, -1, arg, name + ".velocity");
    get_field(L, -2, "rotation");
    motion.rotation = to_vec3(L, -1, arg, name + ".rotation");
    lua_pop(L, 3);
    record.mechanism.push_back(motion);
  }
  lua_pop(L, 1);
  if (get_field(L, idx, "limit") != LUA_TTABLE) {
    throw ArgError(arg, what + ".limit: expected the list of limit interfaces, got " + type_name(L, -1));
  }
  const lua_Integer count = luaL_len(L, -1);
  for (lua_Integer k = 1; k <= count; ++k) {
    lua_rawgeti(L, -1, k);
    const std::string name = what + ".limit[" + std::to_string(k) + "]";
    if (!lua_istable(L, -1)) throw ArgError(arg, name + ": expected { interface, mode, pivot }, got " + type_name(L, -1));
    LimitInterface entry;
    get_field(L, -1, "interface");
    entry.interface = static_cast<int>(check_integer(L, -1, arg, (name + ".interface").c_str())) - 1;
    get_field(L, -2, "mode");
    const char* mode = lua_tostring(L, -1);
    const std::optional<LimitMode> parsed_mode = kLimitModeNames.parse(mode ? mode : "");
    if (!parsed_mode) {
      throw ArgError(arg, name + ".mode: expected " + kLimitModeNames.list() + ", got " +
                          (mode ? "'" + std::string(mode) + "'" : type_name(L, -1)));
    }
    entry.mode = *parsed_mode;
    get_field(L, -3, "pivot");
    entry.pivot = to_vec3(L, -1, arg, name + ".pivot");
    lua_pop(L, 4);
    record.limit.push_back(entry);
  }
  lua_pop(L, 1);
  return record;
}

const std::vector<LimitInterface>* ResultOption::limit() const {
  if (factor) return &factor->limit;
  return analysis && !analysis->limit.empty() ? &analysis->limit : nullptr;
}

const std::vector<BlockMotion>* ResultOption::mechanism() const {
  if (factor) return factor->mechanism.empty() ? nullptr : &factor->mechanism;
  return analysis && !analysis->mechanism.empty() ? &analysis->mechanism : nullptr;
}

ResultOption result_with_mechanism(lua_State* L, const OptionTable& options, const Structure& s,
                                   const ContactOptions& contact) {
  ResultOption chosen;
  if (options.push("result") == LUA_TTABLE) chosen.factor = to_load_factor(L, -1, options.arg(), "result");
  lua_pop(L, 1);
  if (!chosen.factor) {
    chosen.analysis = result_option(L, options);
    return chosen;
  }
  AnalysisSettings analysis;
  analysis.problem = chosen.factor->settings.problem;
  analysis.problem.contact = contact;
  chosen.analysis = std::make_shared<const EquilibriumResult>(
      analyze_equilibrium(structure_at_factor(s, chosen.factor->settings, chosen.factor->factor), analysis));
  return chosen;
}

void set_margin_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"load_factor", w_load_factor},
                                       {"friction_demand", w_friction_demand},
                                       {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
