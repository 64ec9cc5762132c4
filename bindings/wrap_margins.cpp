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

void set_margin_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"load_factor", w_load_factor},
                                       {"friction_demand", w_friction_demand},
                                       {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
