#include "wrap_Result.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <cstring>
#include <sstream>

#include "analysis/compare_methods.hpp"
#include "analysis/cra.hpp"
#include "analysis/equilibrium.hpp"
#include "analysis/qps_export.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_Simulation.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

constexpr const char* kResultMeta = "ashlar.Result";

// What a Lua Result holds: the engine result and what was derived from the
// structure at analysis time (the structure may change afterwards).
struct AnalysisRecord {
  EquilibriumResult result;
  std::optional<Arbitration> check;  // method = "auto": the arbiter's answer (r.check)
  // How tostring names the blocks it mentions (Structure::label), by index.
  std::map<int, std::string> labels;
  std::vector<Vec3> thrust;
  std::vector<std::vector<Vec3>> thrust_branches;
  int block_count = 0;
};

void push_result(lua_State* L, const Structure& structure, EquilibriumResult result,
                 std::optional<Arbitration> check) {
  auto record = std::make_shared<AnalysisRecord>();
  record->result = std::move(result);
  record->check = std::move(check);
  const EquilibriumResult& r = record->result;
  auto keep_label = [&](int block) {
    if (block >= 0 && block < structure.size()) record->labels.emplace(block, structure.label(block));
  };
  if (!r.floating_blocks.empty()) keep_label(r.floating_blocks[0]);
  if (!r.floating_gaps.empty()) keep_label(r.floating_gaps[0].block);
  for (int block : r.failing_blocks) keep_label(block);
  for (const MissedContact& gap : r.failing_gaps) keep_label(gap.block);
  record->thrust = thrust_line(structure, record->result);
  record->thrust_branches = thrust_polylines(structure, record->result);
  record->block_count = structure.size();
  push_boxed(L, std::move(record), kResultMeta, 1);
}

}  // namespace

double friction_option(const OptionTable& options, double fallback) {
  lua_State* L = options.state();
  double friction = fallback;
  if (options.push("friction") != LUA_TNIL) {
    // math.huge (no sliding) is allowed here, unlike in other numbers.
    if (lua_type(L, -1) != LUA_TNUMBER || std::isnan(lua_tonumber(L, -1)) ||
        lua_tonumber(L, -1) < 0.0) {
      throw ArgError(options.arg(), "friction: expected a number >= 0 (math.huge: no sliding), got " +
                                        (lua_type(L, -1) == LUA_TNUMBER ? number_text(lua_tonumber(L, -1)) : type_name(L, -1)));
    }
    friction = lua_tonumber(L, -1);
  }
  lua_pop(L, 1);
  return friction;
}

AnalysisSettings analysis_settings(const OptionTable& options) {
  AnalysisSettings settings;
  EquilibriumOptions& problem = settings.problem;
  problem.friction = friction_option(options, problem.friction);
  problem.friction_sides = static_cast<int>(
      options.whole("friction_sides", 3, 1024, "an integer from 3 to 1024").value_or(problem.friction_sides));
  problem.friction_model = options.choice("friction_model", kFrictionModelNames).value_or(problem.friction_model);
  problem.tension_weight = options.positive("tension_weight", problem.tension_weight, true);
  problem.force_weight = options.positive("force_weight", problem.force_weight);
  problem.contact = contact_options(options, "contact_tolerance", "contact_angle", "contact_min_width",
                                     "contact_min_area");
  settings.solver.tolerance = options.positive("tolerance", settings.solver.tolerance);
  settings.solver.max_iterations = static_cast<int>(
      options.whole("max_iterations", 1, std::numeric_limits<int>::max(), "an integer from 1 to 2^31 - 1").value_or(settings.solver.max_iterations));
  settings.stable_tolerance = options.positive("stable_tolerance", settings.stable_tolerance);
  return settings;
}

void read_method(const OptionTable& options, AnalysisSettings& settings, const char* caller) {
  settings.method = options.choice("method", kAnalysisMethodNames).value_or(settings.method);
  if (caller && is_cra(settings.method)) {
    throw ArgError(options.arg(), std::string("method: '") + kAnalysisMethodNames.name(settings.method) +
                                      "' is not available in " + caller + " (expected 'equilibrium' or 'kinematic')");
  }
}

double bracket_tolerance(const OptionTable& options, double fallback) {
  if (options.has("bracket_tolerance") && options.has("tolerance")) {
    throw ArgError(options.arg(), "bracket_tolerance, tolerance: give one of them (tolerance is bracket_tolerance's "
                                  "older name here)");
  }
  const char* key = options.has("tolerance") ? "tolerance" : "bracket_tolerance";
  const double value = options.positive(key, fallback);
  if (value >= 1.0) {
    throw ArgError(options.arg(), std::string(key) + ": expected a number in (0, 1) (relative width of the final "
                                                     "bracket), got " + number_text(value));
  }
  return value;
}

namespace {

// The options of methods cra and cra_penalty: their own keys, and the
// solver keys they share with the other methods (tolerance and
// max_iterations are IPOPT's, tension_weight the penalty's) at CRA's
// defaults when absent. Their own keys with another method are errors.
void read_cra_options(const OptionTable& options, AnalysisSettings& settings) {
  CraSettings& cra = settings.cra;
  if (options.has("complementarity") && settings.method != AnalysisMethod::cra) {
    throw ArgError(options.arg(), std::string("complementarity: only with method = 'cra' (cra_penalty keeps it exact), "
                                              "got method = '") +
                                      kAnalysisMethodNames.name(settings.method) + "'");
  }
  if (!is_cra(settings.method)) {
    for (const char* key : {"overlap", "displacement_bound"}) {
      if (options.has(key)) {
        throw ArgError(options.arg(), std::string(key) + ": only with method = 'cra' or 'cra_penalty', got method = '" +
                                          kAnalysisMethodNames.name(settings.method) + "'");
      }
    }
    return;
  }
  cra.overlap = options.positive("overlap", cra.overlap, true);
  cra.displacement_bound = options.positive("displacement_bound", cra.displacement_bound);
  cra.complementarity = options.positive("complementarity", cra.complementarity, true);
  cra.tolerance = options.positive("tolerance", cra.tolerance);
  if (options.has("max_iterations")) cra.max_iterations = settings.solver.max_iterations;
  if (options.has("tension_weight")) {
    if (settings.method != AnalysisMethod::cra_penalty) {
      throw ArgError(options.arg(), "tension_weight: not with method = 'cra' (no tension there; use 'cra_penalty')");
    }
    cra.tension_weight = settings.problem.tension_weight;
  }
  check_cra_settings(cra);  // overlap below displacement_bound; guard() reports it
}

}  // namespace

namespace {

// Options table of ashlar.export_qp at stack index arg.
AnalysisSettings settings_from(lua_State* L, int arg) {
  return analysis_settings(OptionTable(L, arg, {ASHLAR_ANALYSIS_OPTIONS, "warm_start"}));
}

std::shared_ptr<AnalysisRecord> check_analysis_record(lua_State* L, int idx) {
  return check_boxed<AnalysisRecord>(L, idx, kResultMeta, "Result");
}

// The arbiter's answer as a Lua table (compare_methods' fields, r.check):
// verdict, stable, decided_by, reason, methods = { equilibrium, kinematic,
// dynamics, cra } (each one's verdict), displacement and displaced_block
// (the dynamics'), friction_demand and margin (mu over it).
void push_arbitration_fields(lua_State* L, const Arbitration& a) {
  set_string(L, "verdict", kVerdictNames.name(a.verdict));
  set_boolean(L, "stable", a.verdict == Verdict::stands);
  if (a.decided_by) set_string(L, "decided_by", kDecidedByNames.name(*a.decided_by));
  push_string(L, a.reason);
  lua_setfield(L, -2, "reason");
  lua_createtable(L, 0, 4);
  set_string(L, "equilibrium", kVerdictNames.name(a.equilibrium));
  set_string(L, "kinematic", kVerdictNames.name(a.kinematic));
  if (a.dynamics) set_string(L, "dynamics", kVerdictNames.name(*a.dynamics));
  if (a.cra) set_string(L, "cra", kVerdictNames.name(*a.cra));
  lua_setfield(L, -2, "methods");
  if (a.dynamics) {
    set_field(L, "displacement", a.displacement);
    if (a.displaced_block >= 0) set_index_field(L, "displaced_block", a.displaced_block);
  }
  if (std::isfinite(a.friction_demand)) {
    set_field(L, "friction_demand", a.friction_demand);
    set_field(L, "margin", a.friction / a.friction_demand);
  }
}

// Option `key` of compare_methods saying when a further opinion runs: nil
// (`absent`), true (always) or false (never).
OpinionWhen opinion_when(const OptionTable& options, const char* key, int type, OpinionWhen absent) {
  if (type == LUA_TNIL) return absent;
  if (type != LUA_TBOOLEAN) {
    throw ArgError(options.arg(), std::string(key) + ": expected true or false, got " +
                                      type_name(options.state(), -1));
  }
  return lua_toboolean(options.state(), -1) ? OpinionWhen::always : OpinionWhen::never;
}

// The Result that carries method = "auto"'s verdict: the method whose
// answer agrees with it (its forces or its mechanism), marked as
// interrupted, and not stable, when there is no verdict.
EquilibriumResult adopted_result(MethodComparison& c) {
  const Arbitration& a = c.arbitration;
  const bool equilibrium_answers = a.verdict == Verdict::stands ? a.decided_by != DecidedBy::both
                                                                : a.decided_by == DecidedBy::equilibrium;
  EquilibriumResult r = std::move(equilibrium_answers ? c.equilibrium : c.kinematic);
  if (a.verdict == Verdict::no_verdict) {
    r.stable = false;
    if (a.interrupted) r.status = SolverStatus::interrupted;
  }
  return r;
}

int w_analyze(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {ASHLAR_ANALYSIS_OPTIONS, "warm_start", "verdict_only", "method", "overlap",
                                     "displacement_bound", "complementarity"});
    AnalysisSettings settings = analysis_settings(options);
    settings.verdict_only = options.boolean("verdict_only").value_or(false);
    // method = "auto": both static methods, and the arbiter where they
    // disagree (compare_methods); the Result of the method that agrees with
    // its verdict, with the verdict in r.check.
    const std::optional<std::string> method = options.string("method");
    const bool automatic = method && *method == "auto";
    if (method && !automatic && !kAnalysisMethodNames.parse(*method)) {
      throw ArgError(2, "method: '" + *method + "' is not one of " + kAnalysisMethodNames.list() + ", auto");
    }
    if (!automatic) read_method(options, settings);
    read_cra_options(options, settings);
    lua_settop(L, 2);
    const bool warm_start = options.push("warm_start") != LUA_TNIL;
    if (automatic && (warm_start || settings.verdict_only)) {
      throw ArgError(2, std::string(warm_start ? "warm_start" : "verdict_only") +
                            ": not with method = 'auto' (it runs every method from rest)");
    }
    if (automatic) {
      MethodComparison c = compare_methods(s, settings);
      EquilibriumResult adopted = adopted_result(c);
      push_result(L, s, std::move(adopted), std::move(c.arbitration));
      return 1;
    }
    if (settings.method == AnalysisMethod::kinematic && warm_start) {
      throw ArgError(2, "warm_start: not with method = \"kinematic\" (its rounds start from no prestress)");
    }
    if (is_cra(settings.method) && (warm_start || settings.verdict_only)) {
      throw ArgError(2, std::string(warm_start ? "warm_start" : "verdict_only") + ": not with method = '" +
                            kAnalysisMethodNames.name(settings.method) + "' (IPOPT solves it whole, from rest)");
    }
    std::shared_ptr<const AnalysisRecord> warm;
    if (warm_start) {
      const Box<AnalysisRecord>* previous = test_boxed<AnalysisRecord>(L, -1, kResultMeta);
      if (!previous) {
        throw ArgError(2, "warm_start: expected a Result of ashlar.analyze, got " +
                              type_name(L, -1));
      }
      if (!previous->ptr) throw ArgError(2, "warm_start: attempt to use a closed Result");
      warm = previous->ptr;
      if (warm->block_count != s.size()) {
        throw ArgError(2, "warm_start: that result is of a structure with " +
                              std::to_string(warm->block_count) + " blocks, this one has " +
                              std::to_string(s.size()));
      }
    }
    luax_pushResult(L, s, analyze_equilibrium(s, settings, warm ? &warm->result : nullptr));
    return 1;
  });
}

int w_compare_methods(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {ASHLAR_ANALYSIS_OPTIONS, "dynamics", "cra", "margin"});
    const AnalysisSettings settings = analysis_settings(options);
    ComparisonSettings comparison;
    // dynamics: nil (where the static methods disagree), true, false, or a
    // table of simulation options (always, with those).
    std::shared_ptr<SimulationProgress> progress;
    const int type = options.push("dynamics");
    if (type == LUA_TTABLE) {
      comparison.dynamics = OpinionWhen::always;
      // The table stays on the stack, under the ground_acceleration and
      // ground_rotation functions the run calls.
      comparison.simulation = simulation_options(
          OptionTable(L, lua_gettop(L), 2, "dynamics.", {ASHLAR_SIMULATION_OPTIONS}), s, progress);
    } else {
      comparison.dynamics = opinion_when(options, "dynamics", type, comparison.dynamics);
      lua_pop(L, 1);
    }
    comparison.cra = opinion_when(options, "cra", options.push("cra"), comparison.cra);
    lua_pop(L, 1);
    if (!options.boolean("margin").value_or(true)) comparison.margin_tolerance = 0.0;
    MethodComparison c = compare_methods(s, settings, comparison);
    if (progress && c.dynamic) progress->finish(*c.dynamic);
    if (c.dynamic) luax_pushSimulation(L, s, std::move(*c.dynamic));
    else lua_pushnil(L);
    luax_pushResult(L, s, std::move(c.equilibrium));
    luax_pushResult(L, s, std::move(c.kinematic));
    if (c.cra) luax_pushResult(L, s, std::move(*c.cra));
    else lua_pushnil(L);
    const std::shared_ptr<const std::vector<Interface>> interfaces_list = s.interfaces(settings.problem.contact);
    const std::vector<Interface>& interfaces = *interfaces_list;
    return call_protected(L, 4, [&](lua_State* L) {
      lua_createtable(L, 0, 16);
      lua_pushvalue(L, 1);  // nil without the dynamic verdict
      lua_setfield(L, -2, "dynamic");
      lua_pushvalue(L, 2);
      lua_setfield(L, -2, "equilibrium");
      lua_pushvalue(L, 3);
      lua_setfield(L, -2, "kinematic");
      lua_pushvalue(L, 4);  // nil without CRA
      lua_setfield(L, -2, "cra");
      lua_createtable(L, static_cast<int>(c.borrowed.size()), 0);
      for (size_t k = 0; k < c.borrowed.size(); ++k) {
        const MethodComparison::Borrowed& entry = c.borrowed[k];
        lua_createtable(L, 0, 5);
        set_field(L, "interface", entry.interface + 1);
        set_index_field(L, "a", interfaces[entry.interface].a);
        set_index_field(L, "b", interfaces[entry.interface].b);
        set_field(L, "friction", entry.friction);
        set_field(L, "available", entry.available);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "borrowed");
      push_arbitration_fields(L, c.arbitration);
      return 1;
    });
  });
}

int w_export_qp(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    const AnalysisSettings settings = settings_from(L, 3);
    write_equilibrium_qps(build_equilibrium_problem(s, settings.problem), path);
    return 0;
  });
}

void push_interfaces(lua_State* L, const EquilibriumResult& result) {
  lua_createtable(L, static_cast<int>(result.interfaces.size()), 0);
  for (size_t i = 0; i < result.interfaces.size(); ++i) {
    const InterfaceForces& f = result.interfaces[i];
    lua_createtable(L, 0, 7);
    set_index_field(L, "a", f.a);
    set_index_field(L, "b", f.b);
    set_field(L, "normal_force", f.normal_force);
    set_field(L, "compression", f.compression);
    set_field(L, "tension", f.tension);
    set_field(L, "resultant", f.resultant);
    set_field(L, "center_of_pressure", f.center_of_pressure);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

// A block's virtual displacement (methods cra, cra_penalty) as
// { translation = {x, y, z} (m), rotation = {x, y, z} (rad) }.
void push_displacement(lua_State* L, const BlockDisplacement& d) {
  lua_createtable(L, 0, 2);
  set_field(L, "translation", d.translation);
  set_field(L, "rotation", d.rotation);
}

void push_displacements(lua_State* L, const EquilibriumResult& result) {
  lua_createtable(L, static_cast<int>(result.displacements.size()), 0);
  for (size_t i = 0; i < result.displacements.size(); ++i) {
    push_displacement(L, result.displacements[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_blocks(lua_State* L, const EquilibriumResult& result) {
  // For floating and failing blocks, the contact they miss (if one is
  // near): scratch memory in a userdata, which Lua frees however this ends.
  const size_t count = result.block_tension.size();
  struct Floating {
    bool floating;
    const MissedContact* missed;
  };
  auto* blocks = static_cast<Floating*>(lua_newuserdatauv(L, std::max<size_t>(count, 1) * sizeof(Floating), 0));
  std::fill(blocks, blocks + count, Floating{false, nullptr});
  for (size_t k = 0; k < result.floating_blocks.size(); ++k) {
    blocks[result.floating_blocks[k]].floating = true;
    if (k < result.floating_gaps.size() && result.floating_gaps[k].block >= 0) {
      blocks[result.floating_blocks[k]].missed = &result.floating_gaps[k];
    }
  }
  for (size_t k = 0; k < result.failing_blocks.size(); ++k) {
    if (k < result.failing_gaps.size() && result.failing_gaps[k].block >= 0) {
      blocks[result.failing_blocks[k]].missed = &result.failing_gaps[k];
    }
  }
  lua_createtable(L, static_cast<int>(count), 0);
  for (size_t i = 0; i < count; ++i) {
    lua_createtable(L, 0, 3);
    set_field(L, "tension", result.block_tension[i]);
    set_field(L, "virtual_torque", result.virtual_torques[i]);
    set_boolean(L, "floating", blocks[i].floating);
    if (i < result.displacements.size()) {
      push_displacement(L, result.displacements[i]);
      lua_setfield(L, -2, "displacement");
    }
    if (const MissedContact* missed = blocks[i].missed) {
      lua_pushinteger(L, missed->block + 1);
      lua_setfield(L, -2, "nearest");
      set_field(L, "gap", missed->tolerance);
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_remove(L, -2);  // the scratch memory
}

void push_vertices(lua_State* L, const EquilibriumResult& result) {
  lua_createtable(L, static_cast<int>(result.vertex_forces.size()), 0);
  for (size_t k = 0; k < result.vertex_forces.size(); ++k) {
    const Eigen::Vector4d& f = result.vertex_forces[k];
    lua_createtable(L, 0, 6);
    set_index_field(L, "interface", result.vertex_interface[k]);
    set_field(L, "position", result.vertex_positions[k]);
    set_field(L, "compression", f(0));
    set_field(L, "tension", f(1));
    set_field(L, "friction_u", f(2));
    set_field(L, "friction_v", f(3));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

void push_cables(lua_State* L, const EquilibriumResult& result) {
  lua_createtable(L, static_cast<int>(result.cables.size()), 0);
  for (size_t c = 0; c < result.cables.size(); ++c) {
    lua_createtable(L, 0, 2);
    set_field(L, "tension", result.cables[c].tension);
    set_field(L, "compression", result.cables[c].compression);
    lua_rawseti(L, -2, static_cast<lua_Integer>(c + 1));
  }
}

// Tables built on first access and kept in the userdata's user value.
int w_Result_thrust_line(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<AnalysisRecord> record = check_analysis_record(L, 1);
    return call_protected(L, 0, [&](lua_State* L) {
      push_points(L, record->thrust);
      return 1;
    });
  });
}

int w_Result_thrust_lines(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<AnalysisRecord> record = check_analysis_record(L, 1);
    const std::vector<std::vector<Vec3>>& branches = record->thrust_branches;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(branches.size()), 0);
      for (size_t k = 0; k < branches.size(); ++k) {
        push_points(L, branches[k]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      return 1;
    });
  });
}

int w_Result_index(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<AnalysisRecord> record = check_analysis_record(L, 1);
    const EquilibriumResult& r = record->result;
    // Not lua_tostring: it would turn a number key into a string, which allocates.
    const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : nullptr;
    if (!key) return 0;
    auto is = [&](const char* name) { return std::strcmp(key, name) == 0; };
    const std::function<std::array<int, 2>(int)> ends_of = [&r](int k) {
      return std::array<int, 2>{r.interfaces[k].a, r.interfaces[k].b};
    };
    lua_pushvalue(L, 1);  // the Result, where push_cached_table keeps its tables
    return call_protected(L, 1, [&](lua_State* L) {
      if (is("thrust_line")) lua_pushcfunction(L, w_Result_thrust_line);
      else if (is("thrust_lines")) lua_pushcfunction(L, w_Result_thrust_lines);
      else if (is("stable")) lua_pushboolean(L, r.stable);
      else if (is("infeasibility")) lua_pushnumber(L, r.infeasibility);
      else if (is("penalty")) lua_pushnumber(L, r.penalty);
      else if (is("objective")) lua_pushnumber(L, r.objective);
      else if (is("status")) lua_pushstring(L, status_name(r.status));
      else if (is("iterations")) lua_pushinteger(L, r.iterations);
      else if (is("factorizations")) lua_pushinteger(L, r.factorizations);
      else if (is("seconds")) lua_pushnumber(L, r.seconds);
      else if (is("imbalance_without_tension")) lua_pushnumber(L, r.imbalance_without_tension);
      else if (is("borderline")) lua_pushboolean(L, r.borderline);
      else if (is("timings")) {
        lua_createtable(L, 0, 4);
        set_field(L, "setup", r.timings.setup);
        set_field(L, "assembly", r.timings.assembly);
        set_field(L, "factorization", r.timings.factorization);
        set_field(L, "solve", r.timings.solve);
      } else if (is("floating") || is("failing")) {
        const std::vector<int>& which = is("floating") ? r.floating_blocks : r.failing_blocks;
        lua_createtable(L, static_cast<int>(which.size()), 0);
        for (size_t i = 0; i < which.size(); ++i) {
          lua_pushinteger(L, which[i] + 1);
          lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
      } else if (is("warnings")) {
        lua_createtable(L, static_cast<int>(r.warnings.size()), 0);
        for (size_t i = 0; i < r.warnings.size(); ++i) {
          push_string(L, r.warnings[i]);
          lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
      } else if (is("method")) {
        lua_pushstring(L, kAnalysisMethodNames.name(r.method));
      } else if (is("check")) {
        if (!record->check) return 0;
        lua_createtable(L, 0, 10);
        push_arbitration_fields(L, *record->check);
      } else if (is("rounds")) {
        lua_pushinteger(L, r.rounds);
      } else if (is("mechanism")) {
        if (r.mechanism.empty()) return 0;
        push_mechanism(L, r.mechanism);
      } else if (is("limit")) {
        push_limit(L, r.limit, ends_of);
      } else if (is("interfaces")) return push_cached_table(L, "interfaces", r, push_interfaces);
      else if (is("blocks")) return push_cached_table(L, "blocks", r, push_blocks);
      else if (is("vertices")) return push_cached_table(L, "vertices", r, push_vertices);
      else if (is("cables")) return push_cached_table(L, "cables", r, push_cables);
      else if (is("displacements")) {
        if (!is_cra(r.method)) return 0;
        return push_cached_table(L, "displacements", r, push_displacements);
      }
      else return 0;
      return 1;
    });
  });
}

int w_Result_tostring(lua_State* L) {
  if (push_if_closed<AnalysisRecord>(L, kResultMeta, "Result")) return 1;
  return guard(L, [&] {
    const std::shared_ptr<AnalysisRecord> record = check_analysis_record(L, 1);
    const EquilibriumResult& r = record->result;
    std::ostringstream text;
    if (r.status == SolverStatus::interrupted) {
      // No verdict: what was computed when it stopped proves nothing.
      text << "Result (no verdict: interrupted after " << r.iterations << " iterations)";
      return push_string(L, text.str());
    }
    text << "Result (" << (r.stable ? "stable" : "unstable") << ", infeasibility " << r.infeasibility << ", "
         << status_name(r.status) << " after " << r.iterations << " iterations";
    auto label = [&](int block) { return record->labels.at(block); };
    if (!r.floating_blocks.empty()) {
      // Why, for the first floating block: what a user must change.
      text << "; " << r.floating_blocks.size() << (r.floating_blocks.size() == 1 ? " block floats" : " blocks float")
           << ": " << label(r.floating_blocks[0]);
      if (!r.floating_gaps.empty() && r.floating_gaps[0].block >= 0) {
        text << " is " << r.floating_gaps[0].tolerance << " m from " << label(r.floating_gaps[0].block)
             << " (contact_tolerance = " << r.floating_gaps[0].tolerance << " closes it)";
      } else {
        text << " touches nothing within 1 % of the structure's size";
      }
    }
    // The first failing block that just misses a contact: the verdict may
    // turn on a joint the tolerance did not find.
    for (size_t k = 0; k < r.failing_gaps.size() && k < r.failing_blocks.size(); ++k) {
      if (r.failing_gaps[k].block < 0) continue;
      text << "; failing " << label(r.failing_blocks[k]) << " is " << r.failing_gaps[k].tolerance << " m from "
           << label(r.failing_gaps[k].block) << " (contact_tolerance = " << r.failing_gaps[k].tolerance
           << " closes it)";
      break;
    }
    if (!r.warnings.empty()) text << "; " << r.warnings.size() << (r.warnings.size() == 1 ? " warning" : " warnings");
    text << ")";
    if (record->check) text << "\nchecked: " << kVerdictNames.name(record->check->verdict) << ": " << record->check->reason;
    return push_string(L, text.str());
  });
}

int w_Result_gc(lua_State* L) { return release_boxed<AnalysisRecord>(L, kResultMeta); }

}  // namespace

void luax_pushResult(lua_State* L, const Structure& structure, EquilibriumResult result) {
  push_result(L, structure, std::move(result), std::nullopt);
}

void push_mechanism(lua_State* L, const std::vector<BlockMotion>& mechanism) {
  lua_createtable(L, static_cast<int>(mechanism.size()), 0);
  for (size_t i = 0; i < mechanism.size(); ++i) {
    lua_createtable(L, 0, 2);
    set_field(L, "velocity", mechanism[i].velocity);
    set_field(L, "rotation", mechanism[i].rotation);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_limit(lua_State* L, const std::vector<LimitInterface>& limit,
                const std::function<std::array<int, 2>(int)>& ends_of) {
  lua_createtable(L, static_cast<int>(limit.size()), 0);
  for (size_t k = 0; k < limit.size(); ++k) {
    const LimitInterface& entry = limit[k];
    const std::array<int, 2> ends = ends_of(entry.interface);
    lua_createtable(L, 0, 7);
    set_field(L, "interface", entry.interface + 1);
    set_index_field(L, "a", ends[0]);
    set_index_field(L, "b", ends[1]);
    set_string(L, "mode", kLimitModeNames.name(entry.mode));
    set_field(L, "pivot", entry.pivot);
    set_field(L, "opening", entry.opening);
    set_field(L, "slip", entry.slip);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

std::shared_ptr<const EquilibriumResult> result_option(lua_State* L, const OptionTable& options) {
  std::shared_ptr<const EquilibriumResult> result;
  if (options.push("result") != LUA_TNIL) {
    result = luax_testResult(L, -1);
    if (!result) {
      throw ArgError(options.arg(), "result: expected a Result of ashlar.analyze (not closed), got " +
                                        type_name(L, -1));
    }
  }
  lua_pop(L, 1);
  return result;
}

std::shared_ptr<const EquilibriumResult> luax_testResult(lua_State* L, int idx) {
  Box<AnalysisRecord>* box = test_boxed<AnalysisRecord>(L, idx, kResultMeta);
  if (!box || !box->ptr) return nullptr;
  return std::shared_ptr<const EquilibriumResult>(box->ptr, &box->ptr->result);
}

void register_Result(lua_State* L) {
  // Fields are computed on access, so __index is a function, not a table.
  static const luaL_Reg metamethods[] = {{"__index", w_Result_index},
                                         {"__tostring", w_Result_tostring},
                                         {"__gc", w_Result_gc},
                                         {"__close", w_Result_gc},
                                         {nullptr, nullptr}};
  register_type(L, kResultMeta, nullptr, metamethods);
}

void set_analysis_functions(lua_State* L) {
  static const luaL_Reg functions[] = {
      {"analyze", w_analyze}, {"compare_methods", w_compare_methods}, {"export_qp", w_export_qp}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
