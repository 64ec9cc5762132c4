// ashlar.optimize: moves a structure's vertices (or a generator's parameters)
// down the structural gradient until the structure stands, or to the least
// material whose margin reaches a target.
#include "wrap_optimize.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "luax.hpp"
#include "optimize/structure_optimization.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

OptimizeSettings optimize_settings(const OptionTable& options) {
  OptimizeSettings settings;
  settings.method = options.choice("method", kOptimizeMethodNames).value_or(settings.method);
  settings.max_iterations = static_cast<int>(
      options.whole("max_iterations", 0, std::numeric_limits<int>::max(), "an integer from 0 to 2^31 - 1").value_or(settings.max_iterations));
  settings.gradient_tolerance = options.positive("gradient_tolerance", settings.gradient_tolerance);
  settings.value_tolerance = options.positive("value_tolerance", settings.value_tolerance);
  settings.initial_step = options.positive("initial_step", settings.initial_step, true);
  if (options.has("bracket_tolerance")) settings.bracket_tolerance = options.positive("bracket_tolerance", 0.0);
  return settings;
}

// opts.objective: "penalty" (the default without a target) descends until
// the structure stands; "volume" or "weight" (the default with a target)
// minimises material subject to the target. Returns the material, or
// nothing for "penalty"; checks the options that go only with one of them.
std::optional<Material> material_objective(const OptionTable& options) {
  const std::optional<std::string> objective = options.string("objective");
  const bool to_target = options.has("target") || (objective && *objective != "penalty");
  if (!to_target) {
    if (options.has("bracket_tolerance")) {
      throw ArgError(2, "bracket_tolerance: only with a target or objective = \"volume\" or \"weight\"");
    }
    return std::nullopt;
  }
  if (objective && *objective == "penalty") {
    throw ArgError(2, "objective: 'penalty' has no target; with a target it is 'volume' or 'weight'");
  }
  if (options.has("method")) {
    throw ArgError(2, "method: not with a target or a material objective, whose search has one method "
                      "(steepest descent to the target, then along the margin's boundary)");
  }
  return options.choice("objective", kMaterialNames).value_or(Material::volume);
}

// The fields of an optimisation to a target: the objective's name and
// value, and the history of the objective and the margin.
void push_target_fields(lua_State* L, Material material, const std::vector<OptimizeStep>& history) {
  set_string(L, "objective", kMaterialNames.name(material));
  set_field(L, "value", history.empty() ? std::nan("") : history.back().value);
  lua_createtable(L, static_cast<int>(history.size()), 0);
  for (size_t k = 0; k < history.size(); ++k) {
    const OptimizeStep& step = history[k];
    lua_createtable(L, 0, 6);
    lua_pushinteger(L, step.iteration);
    lua_setfield(L, -2, "iteration");
    set_field(L, "value", step.value);
    if (!std::isnan(step.margin)) set_field(L, "margin", step.margin);
    set_field(L, "step", step.step);
    set_field(L, "seconds", step.seconds);
    set_boolean(L, "stable", step.stable);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "history");
}

// opts.target: exactly one of stable = true, load_factor = f, geometric_factor
// = g, with the load factor's load and direction, or the geometric factor's
// parameter (a name; by default the only one).
// `names`: the parameters; none when a structure's vertices are optimised.
MarginTarget margin_target(lua_State* L, const OptionTable& options, const std::vector<std::string>& names) {
  MarginTarget target;
  if (options.push("target") != LUA_TTABLE) {
    if (lua_type(L, -1) != LUA_TNIL) {
      throw ArgError(2, "target: expected a table such as { load_factor = 0.2 }, got " + type_name(L, -1));
    }
    lua_pop(L, 1);
    return target;
  }
  const OptionTable t(L, lua_gettop(L), 2, "target.",
                      {"stable", "load_factor", "geometric_factor", "load", "direction", "parameter"});
  const int kinds = t.has("stable") + t.has("load_factor") + t.has("geometric_factor");
  if (kinds != 1) {
    throw ArgError(2, "target: give exactly one of stable = true, load_factor = f, geometric_factor = g; got " +
                          std::to_string(kinds));
  }
  if (t.has("stable") && !t.boolean("stable").value_or(false)) {
    throw ArgError(2, "target.stable: only true is a target");
  }
  if (names.empty() && !t.has("stable")) {
    throw ArgError(2, "target: a structure's vertices are optimised to stable = true only; load_factor and "
                      "geometric_factor need a parametric model");
  }
  if (t.has("load_factor")) {
    target.kind = MarginKind::load_factor;
    target.value = t.positive("load_factor", 0.0, true);
    target.load.pattern = t.choice("load", kLoadPatternNames).value_or(target.load.pattern);
    if (const std::optional<Vec3> direction = t.vec3("direction")) {
      if (target.load.pattern == LoadPattern::point_loads) {
        throw ArgError(2, "target.direction: not with load = 'point_loads' (the loads have their own)");
      }
      target.load.direction = *direction;
    }
  } else {
    for (const char* key : {"load", "direction"}) {
      if (t.has(key)) throw ArgError(2, std::string("target.") + key + ": only with target.load_factor");
    }
  }
  if (t.has("geometric_factor")) {
    target.kind = MarginKind::geometric_factor;
    target.value = t.positive("geometric_factor", 1.0);
    if (const std::optional<std::string> name = t.string("parameter")) {
      const auto it = std::find(names.begin(), names.end(), *name);
      if (it == names.end()) throw ArgError(2, "target.parameter: '" + *name + "' is not one of params");
      target.parameter = static_cast<int>(it - names.begin());
    } else if (names.size() != 1) {
      throw ArgError(2, "target.parameter: required with several params, the one the geometric factor divides");
    }
  } else if (t.has("parameter")) {
    throw ArgError(2, "target.parameter: only with target.geometric_factor");
  }
  lua_pop(L, 1);
  return target;
}

// The analysis options in opts.analysis.
AnalysisSettings nested_analysis_settings(lua_State* L, const OptionTable& options) {
  AnalysisSettings settings;
  if (options.push("analysis") == LUA_TTABLE) {
    settings = analysis_settings(
        OptionTable(L, lua_gettop(L), options.arg(), "analysis.", {ASHLAR_ANALYSIS_OPTIONS}));
  } else if (lua_type(L, -1) != LUA_TNIL) {
    throw ArgError(options.arg(), "analysis: expected a table of ashlar.analyze options, got " +
                                      type_name(L, -1));
  }
  lua_pop(L, 1);
  return settings;
}

// Prints one line per accepted iterate when asked to (or, by default, when
// standard output is a terminal), and keeps the history for Lua.
struct Progress {
  bool print = false;
  const char* material = nullptr;  // optimisation to a target: the objective's name
  struct Entry {
    OptimizeStep step;
    double infeasibility = 0.0;
  };
  std::vector<Entry> history;
  // The last evaluations' (penalty, infeasibility): an accepted iterate is
  // one of them.
  std::vector<std::pair<double, double>> recent;

  void evaluated(double penalty, double infeasibility) {
    recent.emplace_back(penalty, infeasibility);
    if (recent.size() > 64) recent.erase(recent.begin());
  }
  void accepted(const OptimizeStep& step) {
    Entry entry{step, std::nan("")};
    for (auto it = recent.rbegin(); it != recent.rend(); ++it) {
      if (it->first == step.value) {
        entry.infeasibility = it->second;
        break;
      }
    }
    history.push_back(entry);
    if (print && material) {
      std::printf("optimize: iteration %3d  %s %.6g  margin %.6g  step %.3g  %.2f s%s\n", step.iteration,
                  material, step.value, step.margin, step.step, step.seconds,
                  step.stable ? "  reaches the target" : "");
      std::fflush(stdout);
    } else if (print) {
      std::printf("optimize: iteration %3d  penalty %.6g  infeasibility %.6g  step %.3g m  %.2f s%s\n",
                  step.iteration, step.value, entry.infeasibility, step.step, step.seconds,
                  step.stable ? "  stable" : "");
      std::fflush(stdout);
    }
  }
};

bool wants_progress(const OptionTable& options) {
  return options.boolean("progress").value_or(isatty(STDOUT_FILENO) != 0);
}

void push_history(lua_State* L, const Progress& progress) {
  lua_createtable(L, static_cast<int>(progress.history.size()), 0);
  for (size_t k = 0; k < progress.history.size(); ++k) {
    const Progress::Entry& e = progress.history[k];
    lua_createtable(L, 0, 6);
    lua_pushinteger(L, e.step.iteration);
    lua_setfield(L, -2, "iteration");
    set_field(L, "penalty", e.step.value);
    set_field(L, "infeasibility", e.infeasibility);
    set_field(L, "step", e.step.step);
    set_field(L, "seconds", e.step.seconds);
    set_boolean(L, "stable", e.step.stable);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

// {block = i or name, vertex = k} at the top of the stack.
PositionRef vertex_ref(lua_State* L, const Structure& s, int arg, const std::string& what) {
  if (lua_type(L, -1) != LUA_TTABLE) {
    throw ArgError(arg, what + ": expected {block = i, vertex = k}, got " + type_name(L, -1));
  }
  const OptionTable ref(L, lua_gettop(L), arg, what + ".", {"block", "vertex"});
  ref.push("block");
  const int block = check_block_index(L, s, -1, arg, (what + ".block").c_str());
  lua_pop(L, 1);
  ref.push("vertex");
  const lua_Integer vertex = check_integer(L, -1, arg, (what + ".vertex").c_str());
  lua_pop(L, 1);
  const int count = static_cast<int>(s.block(block).vertices().size());
  if (vertex < 1 || vertex > count) {
    throw ArgError(arg, what + ".vertex: " + std::to_string(vertex) + " is out of range (block " +
                            std::to_string(block + 1) + " has " + std::to_string(count) +
                            " vertices)");
  }
  return PositionRef::vertex(block, static_cast<int>(vertex - 1));
}

DesignConstraints design_constraints(lua_State* L, const Structure& s, const OptionTable& options) {
  const int arg = options.arg();
  DesignConstraints c;
  for (int i = 0; i < s.size(); ++i) {
    if (s.is_support(i)) c.fixed_blocks.push_back(i);
  }
  if (options.push("fixed") != LUA_TNIL) {
    for (int block : check_block_list(L, s, -1, arg, "fixed", /*allow_empty=*/true)) c.fixed_blocks.push_back(block);
  }
  lua_pop(L, 1);
  if (const std::optional<std::string> pattern = options.string("fixed_names")) {
    for (int i = 0; i < s.size(); ++i)
      if (matches_pattern(L, s.name(i).c_str(), pattern->c_str())) c.fixed_blocks.push_back(i);
  }
  if (options.push("fixed_vertices") != LUA_TNIL) {
    if (lua_type(L, -1) != LUA_TFUNCTION) {
      throw ArgError(arg, "fixed_vertices: expected a function(point, block, vertex, name) "
                          "returning true for vertices that stay, got " + type_name(L, -1));
    }
    const int predicate = lua_gettop(L);
    for (int i = 0; i < s.size(); ++i) {
      const std::vector<Vec3>& vertices = s.block(i).vertices();
      for (size_t k = 0; k < vertices.size(); ++k) {
        lua_pushvalue(L, predicate);
        push_vec3(L, vertices[k]);
        lua_pushinteger(L, i + 1);
        lua_pushinteger(L, static_cast<lua_Integer>(k + 1));
        lua_pushstring(L, s.name(i).c_str());
        protected_call(L, 4, 1);
        if (lua_toboolean(L, -1)) c.fixed.push_back(PositionRef::vertex(i, static_cast<int>(k)));
        lua_pop(L, 1);
      }
    }
  }
  lua_pop(L, 1);
  if (options.boolean("fixed_cables").value_or(false)) {
    for (size_t p = 0; p < 2 * s.cables().size(); ++p) {
      c.fixed.push_back(PositionRef::point(static_cast<int>(p)));
    }
  }
  if (options.push("together") != LUA_TNIL) {
    if (lua_type(L, -1) != LUA_TTABLE) {
      throw ArgError(arg, "together: expected a list of groups of {block = i, vertex = k}");
    }
    const lua_Integer groups = luaL_len(L, -1);
    for (lua_Integer gi = 1; gi <= groups; ++gi) {
      lua_geti(L, -1, gi);
      const std::string what = "together[" + std::to_string(gi) + "]";
      if (lua_type(L, -1) != LUA_TTABLE) throw ArgError(arg, what + ": expected a list of vertices");
      std::vector<PositionRef> group;
      const lua_Integer members = luaL_len(L, -1);
      for (lua_Integer m = 1; m <= members; ++m) {
        lua_geti(L, -1, m);
        group.push_back(vertex_ref(L, s, arg, what + "[" + std::to_string(m) + "]"));
        lua_pop(L, 1);
      }
      c.move_together.push_back(std::move(group));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  if (options.push("symmetry") != LUA_TNIL) {
    const OptionTable mirror(L, lua_gettop(L), arg, "symmetry.", {"point", "normal"});
    MirrorPlane plane;
    plane.point = mirror.vec3("point").value_or(Vec3::Zero());
    const std::optional<Vec3> normal = mirror.vec3("normal");
    if (!normal) throw ArgError(arg, "symmetry.normal: required, the mirror plane's normal {x, y, z}");
    plane.normal = *normal;
    c.mirror = plane;
  }
  lua_pop(L, 1);
  if (options.push("keep_normal") != LUA_TNIL) {
    if (lua_type(L, -1) != LUA_TTABLE) {
      throw ArgError(arg, "keep_normal: expected a list of {block = i, face = f}");
    }
    const lua_Integer n = luaL_len(L, -1);
    for (lua_Integer k = 1; k <= n; ++k) {
      lua_geti(L, -1, k);
      const std::string what = "keep_normal[" + std::to_string(k) + "]";
      if (lua_type(L, -1) != LUA_TTABLE) throw ArgError(arg, what + ": expected {block = i, face = f}");
      const OptionTable ref(L, lua_gettop(L), arg, what + ".", {"block", "face"});
      ref.push("block");
      const int block = check_block_index(L, s, -1, arg, (what + ".block").c_str());
      lua_pop(L, 1);
      ref.push("face");
      const lua_Integer face = check_integer(L, -1, arg, (what + ".face").c_str());
      lua_pop(L, 1);
      const int faces = static_cast<int>(s.block(block).faces().size());
      if (face < 1 || face > faces) {
        throw ArgError(arg, what + ".face: " + std::to_string(face) + " is out of range (block " +
                                std::to_string(block + 1) + " has " + std::to_string(faces) +
                                " faces)");
      }
      c.keep_normal.push_back({block, static_cast<int>(face - 1)});
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  if (!options.boolean("slide_on_fixed").value_or(false)) hold_faces_on_fixed_blocks(s, c);
  c.max_displacement = options.positive("max_displacement", c.max_displacement);
  c.min_block_volume = options.positive("min_volume", 0.0, true);
  return c;
}

void push_outcome(lua_State* L, OptimizeStatus status, bool stable, const std::string& message,
                  int evaluations, const Progress& progress) {
  set_boolean(L, "stable", stable);
  set_string(L, "status", status_name(status));
  set_string(L, "message", message.c_str());
  lua_pushinteger(L, evaluations);
  lua_setfield(L, -2, "evaluations");
  push_history(L, progress);
  lua_setfield(L, -2, "history");
}

int optimize_structure(lua_State* L) {
  const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
  const Structure& s = *structure;
  s.require_detected_interfaces("optimize");  // before the options: the structure is what is refused
  const OptionTable options(
      L, 2, {"method", "max_iterations", "gradient_tolerance", "value_tolerance", "initial_step",
             "analysis", "progress", "fixed", "fixed_names", "fixed_vertices", "fixed_cables",
             "together", "symmetry", "keep_normal", "max_displacement", "min_volume",
             "slide_on_fixed", "objective", "target", "bracket_tolerance", "smooth", "min_thickness"});
  const AnalysisSettings analysis = nested_analysis_settings(L, options);
  OptimizeSettings settings = optimize_settings(options);
  const std::optional<Material> material = material_objective(options);
  if (!material) {
    for (const char* key : {"smooth", "min_thickness"}) {
      if (options.has(key)) throw ArgError(2, std::string(key) + ": only with objective = \"volume\" or \"weight\"");
    }
  }
  if (material) margin_target(L, options, {});  // checks it: stable = true only
  const DesignConstraints constraints = design_constraints(L, s, options);
  ShapeFabrication fabrication;
  if (options.push("smooth") != LUA_TNIL) {
    if (lua_type(L, -1) != LUA_TTABLE) {
      throw ArgError(2, "smooth: expected { weight = w, curves = { {{block = i, vertex = k}, ...}, ... } }, got " +
                            type_name(L, -1));
    }
    const OptionTable smooth(L, lua_gettop(L), 2, "smooth.", {"weight", "curves"});
    fabrication.smooth_weight = smooth.positive("weight", 0.0, true);
    if (smooth.push("curves") != LUA_TTABLE) throw ArgError(2, "smooth.curves: required, a list of lists of {block = i, vertex = k}");
    const lua_Integer curves = luaL_len(L, -1);
    for (lua_Integer c = 1; c <= curves; ++c) {
      lua_geti(L, -1, c);
      const std::string what = "smooth.curves[" + std::to_string(c) + "]";
      if (lua_type(L, -1) != LUA_TTABLE) throw ArgError(2, what + ": expected a list of {block = i, vertex = k}");
      std::vector<PositionRef> curve;
      const lua_Integer members = luaL_len(L, -1);
      for (lua_Integer m = 1; m <= members; ++m) {
        lua_geti(L, -1, m);
        curve.push_back(vertex_ref(L, s, 2, what + "[" + std::to_string(m) + "]"));
        lua_pop(L, 1);
      }
      fabrication.smooth_curves.push_back(std::move(curve));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  fabrication.min_thickness = options.positive("min_thickness", 0.0, true);
  Progress progress;
  progress.print = wants_progress(options);
  if (material) progress.material = kMaterialNames.name(*material);
  settings.on_step = [&](const OptimizeStep& step) { progress.accepted(step); };
  const StructureOptimization optimized =
      material ? optimize_structure_to_target(s, constraints, analysis, *material, fabrication, settings)
               : optimize_structure(s, constraints, analysis, settings, [&](double penalty, double infeasibility) {
                   progress.evaluated(penalty, infeasibility);
                 });
  const OptimizeResult& result = optimized.result;
  luax_pushStructure(L, optimized.structure);
  return call_protected(L, 1, [&](lua_State* L) {
    lua_createtable(L, 0, 9);
    lua_pushvalue(L, 1);
    lua_setfield(L, -2, "structure");
    push_outcome(L, result.status, result.stable, result.message, result.evaluations, progress);
    if (material) push_target_fields(L, *material, result.history);
    return 1;
  });
}

// Calls the generator at stack index `generator` with a table of `names` =
// `values`; returns the structure it made.
std::shared_ptr<Structure> generate(lua_State* L, int generator, const std::vector<std::string>& names,
                                    const Eigen::VectorXd& values) {
  lua_pushvalue(L, generator);
  call_protected(L, 0, [&](lua_State* L) {  // the parameters
    lua_createtable(L, 0, static_cast<int>(names.size()));
    for (size_t j = 0; j < names.size(); ++j) {
      lua_pushnumber(L, values(j));
      lua_setfield(L, -2, names[j].c_str());
    }
    return 1;
  });
  protected_call(L, 1, 1);
  std::shared_ptr<Structure> s = luax_checkStructure(L, -1);
  lua_pop(L, 1);
  return s;
}

int optimize_parameters_of(lua_State* L) {
  const int generator = 1;
  const OptionTable options(L, 2, {"params", "lower", "upper", "method", "max_iterations",
                                   "gradient_tolerance", "value_tolerance", "initial_step",
                                   "analysis", "progress", "objective", "target", "bracket_tolerance"});
  std::vector<std::string> names;
  std::vector<double> initial;
  if (options.push("params") != LUA_TTABLE) {
    throw ArgError(2, "params: required, a table of parameter names and starting values");
  }
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING) throw ArgError(2, "params: keys must be parameter names");
    const std::string name = lua_tostring(L, -2);
    initial.push_back(check_number(L, -1, 2, ("params." + name).c_str()));
    names.push_back(name);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  const int n = static_cast<int>(names.size());
  if (n == 0) throw ArgError(2, "params: give at least one parameter to optimise");
  // Deterministic order: sorted by name.
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = j;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return names[a] < names[b]; });
  std::vector<std::string> sorted_names;
  Eigen::VectorXd start(n), lower(n), upper(n);
  for (int j = 0; j < n; ++j) {
    sorted_names.push_back(names[order[j]]);
    start(j) = initial[order[j]];
  }
  for (const char* side : {"lower", "upper"}) {
    Eigen::VectorXd& bound = side[0] == 'l' ? lower : upper;
    bound.setConstant(side[0] == 'l' ? -std::numeric_limits<double>::infinity()
                                     : std::numeric_limits<double>::infinity());
    if (options.push(side) == LUA_TTABLE) {
      for (int j = 0; j < n; ++j) {
        if (get_field(L, -1, sorted_names[j].c_str()) != LUA_TNIL) {
          bound(j) = check_number(L, -1, 2, (std::string(side) + "." + sorted_names[j]).c_str());
        }
        lua_pop(L, 1);
      }
    } else if (lua_type(L, -1) != LUA_TNIL) {
      throw ArgError(2, std::string(side) + ": expected a table of parameter bounds");
    }
    lua_pop(L, 1);
  }
  const AnalysisSettings analysis = nested_analysis_settings(L, options);
  OptimizeSettings settings = optimize_settings(options);
  const std::optional<Material> material = material_objective(options);
  const bool to_target = material.has_value();
  const MarginTarget target = margin_target(L, options, sorted_names);
  Progress progress;
  progress.print = wants_progress(options);
  if (to_target) progress.material = kMaterialNames.name(*material);
  settings.on_step = [&](const OptimizeStep& step) { progress.accepted(step); };
  const StructureGenerator generator_of = [&](const Eigen::VectorXd& values) {
    return generate(L, generator, sorted_names, values);
  };
  const GeneratedOptimization optimized =
      to_target ? optimize_generated_to_target(generator_of, sorted_names, lower, upper, start, analysis, target,
                                               *material, settings)
                : optimize_generated(generator_of, sorted_names, lower, upper, start, analysis, settings,
                                     [&](double penalty, double infeasibility) {
                                       progress.evaluated(penalty, infeasibility);
                                     });
  const ParameterResult& result = optimized.result;
  luax_pushStructure(L, optimized.structure);
  return call_protected(L, 1, [&](lua_State* L) {
    lua_createtable(L, 0, 12);
    lua_createtable(L, 0, n);
    for (int j = 0; j < n; ++j) {
      lua_pushnumber(L, result.parameters(j));
      lua_setfield(L, -2, sorted_names[j].c_str());
    }
    lua_setfield(L, -2, "params");
    lua_pushvalue(L, 1);
    lua_setfield(L, -2, "structure");
    lua_createtable(L, 0, 0);
    for (int j = 0; j < n; ++j) {
      if (result.active_bounds[j] == BoundSide::none) continue;
      set_string(L, sorted_names[j].c_str(), kBoundSideNames.name(result.active_bounds[j]));
    }
    lua_setfield(L, -2, "active_bounds");
    push_outcome(L, result.status, result.stable, result.message, result.evaluations, progress);
    if (to_target) {
      push_target_fields(L, *material, result.history);
      if (!std::isnan(result.margin)) set_field(L, "margin", result.margin);
      set_boolean(L, "on_boundary", result.on_boundary);
    }
    return 1;
  });
}

int w_optimize(lua_State* L) {
  return guard(L, [&] {
    if (lua_type(L, 1) == LUA_TFUNCTION) return optimize_parameters_of(L);
    return optimize_structure(L);
  });
}

}  // namespace

void set_optimize_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"optimize", w_optimize}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
