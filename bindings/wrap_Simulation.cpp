#include "wrap_Simulation.hpp"

#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>

#include "core/text.hpp"
#include "io/mesh_io.hpp"
#include "io/simulation_export.hpp"
#include "io/viewer_page.hpp"
#include "sandbox.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"
#include "wrap_colors.hpp"
#include "wrap_export.hpp"

namespace ashlar::lua {

namespace {

constexpr const char* kSimulationMeta = "ashlar.Simulation";

// What a Lua Simulation holds: the run and the structure it ran on (a copy:
// the Lua structure may change afterwards; blocks are shared).
struct SimulationRecord {
  Structure structure;
  SimulationResult result;
};

std::shared_ptr<SimulationRecord> check_record(lua_State* L, int idx) {
  return check_boxed<SimulationRecord>(L, idx, kSimulationMeta, "Simulation");
}

Vec3 call_ground_acceleration(lua_State* L, int function, int arg, double t) {
  lua_pushvalue(L, function);
  lua_pushnumber(L, t);
  protected_call(L, 1, 3);
  Vec3 a;
  for (int k = 0; k < 3; ++k) {
    const int idx = lua_gettop(L) - 2 + k;
    if (lua_type(L, idx) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, idx))) {
      const std::string got = lua_type(L, idx) == LUA_TNUMBER ? number_text(lua_tonumber(L, idx)) : type_name(L, idx);
      lua_pop(L, 3);
      throw ArgError(arg, "ground_acceleration: the function must return three finite numbers ax, ay, az (m/s^2); at t = " +
                              number_text(t) + " its result " + std::to_string(k + 1) + " is " + got);
    }
    a[k] = lua_tonumber(L, idx);
  }
  lua_pop(L, 3);
  return a;
}

int w_Simulation_trajectory(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_record(L, 1);
    const int i = check_block_index(L, record->structure, 2, 2, "block");
    const SimulationResult& r = record->result;
    const int frames = static_cast<int>(r.times.size());
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 3);
      lua_createtable(L, frames, 0);
      for (int k = 0; k < frames; ++k) {
        lua_pushnumber(L, r.times[k]);
        lua_rawseti(L, -2, k + 1);
      }
      lua_setfield(L, -2, "times");
      lua_createtable(L, frames, 0);
      for (int k = 0; k < frames; ++k) {
        push_vec3(L, r.poses[k][i].position);
        lua_rawseti(L, -2, k + 1);
      }
      lua_setfield(L, -2, "positions");
      lua_createtable(L, frames, 0);
      for (int k = 0; k < frames; ++k) {
        push_vec3(L, rotation_vector(r.poses[k][i].rotation));
        lua_rawseti(L, -2, k + 1);
      }
      lua_setfield(L, -2, "rotations");
      return 1;
    });
  });
}

int w_Simulation_export(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_record(L, 1);
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    const OptionTable options(L, 3, {ASHLAR_EXPORT_OPTIONS, "frame", "fps", "autoplay"});
    const SimulationResult& r = record->result;
    const int frames = static_cast<int>(r.times.size());
    if (const std::optional<lua_Integer> frame =
            options.whole("frame", 1, frames, "a frame number from 1 to " + std::to_string(frames))) {
      if (options.has("fps")) throw ArgError(3, "fps: a still (frame = k) has no frame rate");
      if (options.has("autoplay")) throw ArgError(3, "autoplay: a still (frame = k) does not play");
      const Structure still = posed_structure(record->structure, r.poses[*frame - 1]);
      export_with_options(L, still, path, options);
      return 0;
    }
    const std::optional<std::string> format = options.string("format");
    if (format && *format != "html") {
      throw ArgError(3, "format: an animation is a .glb, or the HTML viewer with format = \"html\", got \"" +
                            *format + "\" (give frame = k for a still in any format)");
    }
    const bool html = format || file_extension(path) == "html";
    for (const char* key : {"interfaces", "tolerance", "result", "forces", "thrust", "force_scale", "cable_color",
                            "traces", "trace_color", "mechanism", "limit"}) {
      if (options.has(key)) {
        throw ArgError(3, std::string(key) + ": applies to a still (give frame = k); an animation takes color and "
                                             "fps, and as a page (.html) legend, opacity, edges and title too");
      }
    }
    if (!html) {
      if (options.has("autoplay")) {
        throw ArgError(3, "autoplay: applies to an animated page (.html, or format = \"html\"); a .glb animation "
                          "plays as its viewer says");
      }
      for (const char* key : {"opacity", "edges", "title", "legend"}) {
        if (options.has(key)) {
          throw ArgError(3, std::string(key) + ": applies to a still (give frame = k) or an animated page (.html, "
                                               "or format = \"html\"); a .glb animation takes color and fps");
        }
      }
    }
    const double fps = options.positive("fps", 0.0, true);
    if (html) {
      ExportOptions page = block_appearance(L, options, record->structure.size(), true);
      page.autoplay = options.boolean("autoplay").value_or(true);
      write_viewer_page(record->structure, r, fps, path, page);
      return 0;
    }
    AnimationOptions animation;
    animation.block_colors = block_colors(L, options, record->structure.size());
    animation.fps = fps;
    export_animation(record->structure, r, path, animation);
    return 0;
  });
}

int w_Simulation_structure(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_record(L, 1);
    const SimulationResult& r = record->result;
    const int frames = static_cast<int>(r.times.size());
    const lua_Integer frame = check_integer(L, 2, "frame");
    if (frame < 1 || frame > frames) {
      throw ArgError(2, "frame: expected a frame number from 1 to " + std::to_string(frames) + ", got " +
                            std::to_string(frame));
    }
    luax_pushStructure(L, std::make_shared<Structure>(posed_structure(record->structure, r.poses[frame - 1])));
    return 1;
  });
}

void push_displacements(lua_State* L, const SimulationResult& r) {
  lua_createtable(L, static_cast<int>(r.displacement.size()), 0);
  for (size_t i = 0; i < r.displacement.size(); ++i) {
    lua_pushnumber(L, r.displacement[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

int w_Simulation_index(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_record(L, 1);
    const SimulationResult& r = record->result;
    // Not lua_tostring: it would turn a number key into a string, which allocates.
    const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : nullptr;
    if (!key) return 0;
    const bool verdict = r.status == SimulationStatus::completed;
    auto is = [&](const char* name) { return std::strcmp(key, name) == 0; };
    lua_pushvalue(L, 1);  // the userdata, where push_cached_table keeps its tables
    return call_protected(L, 1, [&](lua_State* L) {
      if (is("trajectory")) lua_pushcfunction(L, w_Simulation_trajectory);
      else if (is("export")) lua_pushcfunction(L, w_Simulation_export);
      else if (is("structure")) lua_pushcfunction(L, w_Simulation_structure);
      else if (is("status")) lua_pushstring(L, kSimulationStatusNames.name(r.status));
      else if (is("moved")) {
        if (!verdict) return 0;
        lua_pushboolean(L, r.moved);
      } else if (is("settled")) {
        if (!verdict) return 0;
        lua_pushboolean(L, r.settled);
      } else if (is("max_displacement")) lua_pushnumber(L, r.max_displacement);
      else if (is("max_displacement_block")) {
        if (r.max_displacement_block < 0) return 0;
        lua_pushinteger(L, r.max_displacement_block + 1);
      } else if (is("steps")) lua_pushinteger(L, r.steps);
      else if (is("time")) lua_pushnumber(L, r.time);
      else if (is("seconds")) lua_pushnumber(L, r.seconds);
      else if (is("frames")) lua_pushinteger(L, static_cast<lua_Integer>(r.times.size()));
      else if (is("sweeps")) lua_pushinteger(L, static_cast<lua_Integer>(r.sweeps));
      else if (is("unconverged_steps")) lua_pushinteger(L, r.unconverged_steps);
      else if (is("searches")) lua_pushinteger(L, r.searches);
      else if (is("max_active_contacts")) lua_pushinteger(L, r.max_active_contacts);
      else if (is("global_steps")) lua_pushinteger(L, static_cast<lua_Integer>(r.global_steps));
      else if (is("factorizations")) lua_pushinteger(L, static_cast<lua_Integer>(r.factorizations));
      else if (is("max_residual")) lua_pushnumber(L, r.max_residual);
      else if (is("max_residual_time")) {
        if (r.max_residual_blocks.first < 0) return 0;
        lua_pushnumber(L, r.max_residual_time);
      } else if (is("max_residual_blocks")) {
        if (r.max_residual_blocks.first < 0) return 0;
        lua_createtable(L, 2, 0);
        lua_pushinteger(L, r.max_residual_blocks.first + 1);
        lua_rawseti(L, -2, 1);
        lua_pushinteger(L, r.max_residual_blocks.second + 1);
        lua_rawseti(L, -2, 2);
      }
      else if (is("displacements")) return push_cached_table(L, "displacements", r, push_displacements);
      else return 0;
      return 1;
    });
  });
}

int w_Simulation_tostring(lua_State* L) {
  if (push_if_closed<SimulationRecord>(L, kSimulationMeta, "Simulation")) return 1;
  return guard(L, [&] {
    const SimulationResult& r = check_record(L, 1)->result;
    std::ostringstream text;
    text << "Simulation (" << kSimulationStatusNames.name(r.status) << ", " << r.steps << " steps to t = " << r.time
         << " s";
    if (r.status == SimulationStatus::completed) {
      text << ", " << (r.moved ? "moved" : "stayed") << ", " << (r.settled ? "settled" : "still moving");
    }
    text << ", largest displacement " << message_number(r.max_displacement) << " m)";
    return push_string(L, text.str());
  });
}

int w_Simulation_gc(lua_State* L) { return release_boxed<SimulationRecord>(L, kSimulationMeta); }

int w_simulate(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const OptionTable options(L, 2, {ASHLAR_SIMULATION_OPTIONS, "friction", "contact_tolerance", "contact_angle"});
    std::shared_ptr<SimulationProgress> progress;
    SimulationOptions settings = simulation_options(options, *structure, progress);
    settings.friction = friction_option(options, settings.friction);
    settings.contact = contact_options(options, "contact_tolerance", "contact_angle", nullptr, nullptr);
    SimulationResult result = simulate(*structure, settings);
    if (progress) progress->finish(result);
    luax_pushSimulation(L, *structure, std::move(result));
    return 1;
  });
}

}  // namespace

SimulationProgress::SimulationProgress(const std::string& label, std::size_t steps)
    : line_(label, steps, true, stderr, 10.0, "simulate", "step") {}

SimulationProgress::~SimulationProgress() {
  if (!finished_) line_.finish(done_, 0, "stopped by an error");
}

void SimulationProgress::update(std::size_t done) {
  done_ = done;
  line_.update(done, 0);
}

void SimulationProgress::finish(const SimulationResult& result) {
  finished_ = true;
  std::string note = kSimulationStatusNames.name(result.status);
  if (result.status == SimulationStatus::completed) {
    note += std::string(result.moved ? ", moved" : ", stayed") + (result.settled ? ", settled" : ", still moving");
  }
  line_.finish(static_cast<std::size_t>(result.steps), 0, note);
}

SimulationOptions simulation_options(const OptionTable& options, const Structure& structure,
                                     std::shared_ptr<SimulationProgress>& progress) {
  lua_State* L = options.state();
  const int arg = options.arg();
  SimulationOptions o;
  o.duration = options.positive("duration", o.duration);
  o.step = options.positive("step", o.step);
  o.theta = options.number("theta", o.theta);
  o.restitution = options.number("restitution", o.restitution);
  if (const std::optional<Vec3> gravity = options.vec3("gravity")) o.gravity = *gravity;
  o.record_every = static_cast<int>(
      options.whole("record_every", 0, 1 << 30, "a number of steps >= 0 (0: automatic)").value_or(o.record_every));
  o.search_distance = options.positive("search_distance", o.search_distance, true);
  o.moved_fraction = options.positive("moved_fraction", o.moved_fraction);
  o.settle_speed = options.positive("settle_speed", o.settle_speed);
  o.max_sweeps = static_cast<int>(options.whole("max_sweeps", 1, 1 << 30, "a whole number >= 1").value_or(o.max_sweeps));
  o.tolerance = options.positive("tolerance", o.tolerance);
  const int type = options.push("ground_acceleration");
  if (type == LUA_TFUNCTION) {
    // Stays on the stack for the run.
    const int function = lua_gettop(L);
    o.ground_acceleration = [L, function, arg](double t) { return call_ground_acceleration(L, function, arg, t); };
  } else {
    if (type != LUA_TNIL) {
      throw ArgError(arg, "ground_acceleration: expected a function(t) returning ax, ay, az (m/s^2), got " +
                              type_name(L, -1));
    }
    lua_pop(L, 1);
  }
  if (options.boolean("progress").value_or(false)) {
    const auto steps = static_cast<std::size_t>(std::ceil(o.duration / o.step - 1e-9));
    const double step = o.step;
    progress = std::make_shared<SimulationProgress>(std::to_string(structure.size()) + " blocks", steps);
    SimulationProgress* line = progress.get();
    o.progress = [line, step](double t) { line->update(static_cast<std::size_t>(std::lround(t / step))); };
  }
  return o;
}

void luax_pushSimulation(lua_State* L, const Structure& structure, SimulationResult result) {
  auto record = std::make_shared<SimulationRecord>(SimulationRecord{structure, std::move(result)});
  push_boxed(L, std::move(record), kSimulationMeta, 1);
}

void register_Simulation(lua_State* L) {
  // Fields are read on access, so __index is a function, not a table.
  static const luaL_Reg metamethods[] = {{"__index", w_Simulation_index},
                                         {"__tostring", w_Simulation_tostring},
                                         {"__gc", w_Simulation_gc},
                                         {"__close", w_Simulation_gc},
                                         {nullptr, nullptr}};
  register_type(L, kSimulationMeta, nullptr, metamethods);
}

void set_simulation_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"simulate", w_simulate}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
