// ashlar.tilt, ashlar.geometric_factor and ashlar.refine: a structure turned
// on a tilt table, the smallest value of a model's parameter at which the
// model stands (Heyman's geometric factor of safety), and the coarsest
// discretisation of a model whose answer has settled.
//
// The searches themselves are the engine's (analysis/parameter_search.hpp);
// their callbacks here call the Lua functions (the model, the criterion, the
// metric) and warm-start the default criterion's analyses.
#include "wrap_search.hpp"

#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "analysis/equilibrium.hpp"
#include "analysis/equilibrium_analysis.hpp"
#include "analysis/parameter_search.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "luax.hpp"
#include "structure/structure_transform.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ----------------------------------------------------------------------------
// Lua helpers.

// A number as Lua prints it ("0.3", not "0.29999999999999999").
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.14g", value);
  return text;
}

// "nil", or the value's type with an article: "a number", "a Block".
std::string a_value(lua_State* L, int idx) {
  if (lua_isnil(L, idx)) return "nil";
  const std::string name = type_name(L, idx);
  return (std::string("aeiouAEIOU").find(name[0]) != std::string::npos ? "an " : "a ") + name;
}

// An integer field of the table on top of the stack (set_field's would be a float).
void set_integer(lua_State* L, const char* key, lua_Integer value) {
  lua_pushinteger(L, value);
  lua_setfield(L, -2, key);
}

void check_function(lua_State* L, int arg, const char* what, const char* expected) {
  if (lua_type(L, arg) != LUA_TFUNCTION) {
    throw ArgError(arg, std::string(what) + ": expected " + expected + ", got " + type_name(L, arg));
  }
}

// Calls the function pushed below its `nargs` arguments, leaving one result;
// its error becomes an Error that starts with `call` (e.g. "refine:
// metric_fn(s, 16)") and keeps the error's own file:line.
void call_lua(lua_State* L, int nargs, const std::string& call) {
  try {
    protected_call(L, nargs, 1);
  } catch (const std::runtime_error& e) {
    throw Error(call + " failed: " + e.what());
  }
}

// The Structure on top of the stack, which `call` returned.
std::shared_ptr<Structure> returned_structure(lua_State* L, const std::string& call) {
  if (type_name(L, -1) != "Structure") {
    throw Error(call + " returned " + a_value(L, -1) + ", expected a Structure");
  }
  try {
    return luax_checkStructure(L, -1);
  } catch (const ArgError& e) {
    throw Error(call + " returned a Structure that cannot be used: " + e.what());
  }
}

// ----------------------------------------------------------------------------
// ashlar.tilt

int w_tilt(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const double angle = check_number(L, 2, "angle");
    const OptionTable options(L, 3, {"axis", "origin"});
    const Vec3 axis = options.vec3("axis").value_or(Vec3::UnitY());
    if (axis.norm() == 0.0) throw ArgError(3, "axis: expected a non-zero vector, got {0, 0, 0}");
    const Vec3 origin = options.vec3("origin").value_or(base_center(s));
    luax_pushStructure(L, std::make_shared<Structure>(rotated(s, axis, angle, origin)));
    return 1;
  });
}

// ----------------------------------------------------------------------------
// ashlar.geometric_factor

// The history entry of one value, pushed as a table.
void push_probe(lua_State* L, const ThresholdProbe& probe) {
  lua_createtable(L, 0, 6);
  set_field(L, "value", probe.value);
  set_boolean(L, "stable", probe.verdict.stands);
  if (const auto& analysis = probe.verdict.analysis) {
    set_field(L, "infeasibility", analysis->infeasibility);
    set_integer(L, "iterations", analysis->iterations);
    set_string(L, "status", status_name(analysis->status));
  }
  set_field(L, "seconds", probe.seconds);
}

int w_geometric_factor(lua_State* L) {
  return guard(L, [&] {
    const auto start = Clock::now();
    check_function(L, 1, "model_fn", "a function(value) returning a Structure");
    const double value = check_number(L, 2, "value");
    if (value <= 0.0) {
      throw ArgError(2, "value: expected a number > 0 (the parameter's current value), got " +
                            number_text(value));
    }
    const OptionTable options(
        L, 3, {ASHLAR_ANALYSIS_OPTIONS, "bracket_tolerance", "lower", "upper", "max_analyses", "stands"});
    AnalysisSettings settings = analysis_settings(options);
    // `tolerance` is the bracket's here (bracket_tolerance's older name);
    // the analyses keep the solver's own.
    settings.solver.tolerance = InteriorPointSettings{}.tolerance;
    ThresholdSettings search;
    search.bracket_tolerance = bracket_tolerance(options, search.bracket_tolerance);
    const double lower = options.positive("lower", 0.0, true);
    if (lower >= value) {
      throw ArgError(3, "lower: expected a number >= 0 and < value (" + number_text(value) +
                            "), got " + number_text(lower));
    }
    search.floor = lower > 0.0 ? lower : kThresholdFloorFraction * value;
    search.ceiling = options.number("upper", kThresholdCeilingMultiple * value);
    if (search.ceiling <= value) {
      throw ArgError(3, "upper: expected a number > value (" + number_text(value) + "), got " +
                            number_text(search.ceiling));
    }
    search.max_evaluations = static_cast<int>(
        options.whole("max_analyses", 1, INT_MAX, "a whole number >= 1").value_or(search.max_evaluations));
    int criterion = 0;  // stack index of `stands`, 0 for the default
    if (options.push("stands") != LUA_TNIL) {
      if (lua_type(L, -1) != LUA_TFUNCTION) {
        throw ArgError(3, "stands: expected a function(s, value) returning true when s stands, "
                          "got " + type_name(L, -1));
      }
      criterion = lua_gettop(L);
      for (const char* key : {ASHLAR_ANALYSIS_OPTIONS}) {
        if (std::string(key) != "tolerance" && options.has(key)) {  // tolerance: the bracket's
          throw ArgError(3, std::string(key) + ": analysis options apply to the default "
                                               "criterion; with stands, analyse in that function");
        }
      }
    } else {
      lua_pop(L, 1);
    }

    // Successive models differ only in their dimensions: one analysis
    // object, warm from the last optimum.
    AnalysisSequence analyses(settings, true);
    const auto stands = [&](double v) {
      const std::string call = "geometric_factor: model_fn(" + number_text(v) + ")";
      lua_pushvalue(L, 1);
      lua_pushnumber(L, v);
      call_lua(L, 1, call);
      const std::shared_ptr<Structure> s = returned_structure(L, call);
      ThresholdVerdict verdict;
      if (criterion) {
        lua_pushvalue(L, criterion);
        lua_pushvalue(L, -2);
        lua_pushnumber(L, v);
        const std::string asked = "geometric_factor: stands(s, " + number_text(v) + ")";
        call_lua(L, 2, asked);
        if (!lua_isboolean(L, -1)) {
          throw Error(asked + " returned " + a_value(L, -1) + ", expected a boolean");
        }
        verdict.stands = lua_toboolean(L, -1);
        lua_pop(L, 1);
      } else {
        const EquilibriumResult result = analyses.analyze(*s);
        verdict.stands = result.stable;
        verdict.analysis = VerdictAnalysis{result.infeasibility, result.iterations, result.status};
      }
      lua_pop(L, 1);  // the structure
      return verdict;
    };
    const Threshold found = find_threshold(value, search, stands);

    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 8);
      const bool has_minimum = !std::isnan(found.stable);
      if (has_minimum) set_field(L, "minimum", found.stable);
      set_field(L, "factor", has_minimum ? value / found.stable : 0.0);
      set_string(L, "status", threshold_status_name(found.status));
      if (!std::isnan(found.unstable)) set_field(L, "lower", found.unstable);
      if (!std::isnan(found.stable)) set_field(L, "upper", found.stable);
      set_integer(L, "analyses", found.evaluations);
      lua_createtable(L, static_cast<int>(found.history.size()), 0);
      for (size_t k = 0; k < found.history.size(); ++k) {
        push_probe(L, found.history[k]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "history");
      set_field(L, "seconds", seconds_since(start));
      return 1;
    });
  });
}

// ----------------------------------------------------------------------------
// ashlar.refine

int w_refine(lua_State* L) {
  return guard(L, [&] {
    const auto start = Clock::now();
    check_function(L, 1, "model_fn", "a function(n) returning a Structure of n parts");
    check_function(L, 2, "metric_fn", "a function(s, n) returning a number");
    const OptionTable options(L, 3, {"tolerance", "start", "growth", "max", "confirm"});
    RefineSettings settings;
    settings.tolerance = options.positive("tolerance", settings.tolerance);
    settings.start = static_cast<int>(
        options.whole("start", 1, INT_MAX, "a whole number >= 1").value_or(settings.start));
    settings.max = static_cast<int>(
        options.whole("max", 1, INT_MAX, "a whole number >= 1").value_or(settings.max));
    if (settings.start > settings.max) {
      throw ArgError(3, "start: expected a whole number <= max (" + std::to_string(settings.max) +
                            "), got " + std::to_string(settings.start));
    }
    settings.growth = options.number("growth", settings.growth);
    if (settings.growth < 1.0) {
      throw ArgError(3, "growth: expected a number >= 1 (the factor from one count to the "
                        "next), got " + number_text(settings.growth));
    }
    settings.confirm = static_cast<int>(
        options.whole("confirm", 1, INT_MAX, "a whole number >= 1").value_or(settings.confirm));

    // Each count's model, in history order, kept for the result.
    call_protected(L, 0, [](lua_State* L) {
      lua_newtable(L);
      return 1;
    });
    const int models = lua_gettop(L);
    const auto metric = [&](int n) {
      const std::string count = std::to_string(n);
      const std::string call = "refine: model_fn(" + count + ")";
      lua_pushvalue(L, 1);
      lua_pushinteger(L, n);
      call_lua(L, 1, call);
      returned_structure(L, call);
      lua_pushvalue(L, models);
      lua_pushvalue(L, -2);
      call_protected(L, 2, [](lua_State* L) {  // appended to the models
        lua_rawseti(L, 1, static_cast<lua_Integer>(lua_rawlen(L, 1) + 1));
        return 0;
      });
      const std::string measured = "refine: metric_fn(s, " + count + ")";
      lua_pushvalue(L, 2);
      lua_insert(L, -2);
      lua_pushinteger(L, n);
      call_lua(L, 2, measured);
      const bool number = lua_type(L, -1) == LUA_TNUMBER;
      const double value = number ? lua_tonumber(L, -1) : kNaN;
      if (!std::isfinite(value)) {
        throw Error(measured + " returned " +
                    (number ? number_text(value) + ", expected a finite number"
                            : a_value(L, -1) + ", expected a number"));
      }
      lua_pop(L, 1);
      return value;
    };
    const Refinement refinement = refine_count(settings, metric);

    const RefineStep& adequate = refinement.history[refinement.adequate];
    const double seconds = seconds_since(start);
    lua_pushvalue(L, models);
    return call_protected(L, 1, [&](lua_State* L) {
      lua_createtable(L, 0, 7);
      set_integer(L, "count", adequate.count);
      lua_rawgeti(L, 1, static_cast<lua_Integer>(refinement.adequate + 1));  // its model
      lua_setfield(L, -2, "structure");
      set_field(L, "value", adequate.value);
      set_boolean(L, "converged", refinement.converged);
      set_field(L, "reference", refinement.history.back().value);
      lua_createtable(L, static_cast<int>(refinement.history.size()), 0);
      for (size_t k = 0; k < refinement.history.size(); ++k) {
        const RefineStep& step = refinement.history[k];
        lua_createtable(L, 0, 4);
        set_integer(L, "count", step.count);
        set_field(L, "value", step.value);
        if (!std::isnan(step.change)) set_field(L, "change", step.change);
        set_field(L, "seconds", step.seconds);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "history");
      set_field(L, "seconds", seconds);
      return 1;
    });
  });
}

}  // namespace

void set_search_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"tilt", w_tilt},
                                       {"geometric_factor", w_geometric_factor},
                                       {"refine", w_refine},
                                       {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
