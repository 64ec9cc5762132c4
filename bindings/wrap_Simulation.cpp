#include "wrap_Simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <sstream>

#include "core/text.hpp"
#include "dynamics/ground_motion.hpp"
#include "dynamics/simulation_summary.hpp"
#include "io/chart.hpp"
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
constexpr const char* kGroundMotionMeta = "ashlar.GroundMotion";

// What a Lua Simulation holds: the run and the structure it ran on (a copy:
// the Lua structure may change afterwards; blocks are shared), and the
// run's moved_fraction, the summary's default.
struct SimulationRecord {
  Structure structure;
  SimulationResult result;
  double moved_fraction = SimulationOptions{}.moved_fraction;
};

std::shared_ptr<GroundMotion> check_ground_motion(lua_State* L, int idx) {
  return check_boxed<GroundMotion>(L, idx, kGroundMotionMeta, "GroundMotion");
}

std::shared_ptr<SimulationRecord> check_simulation_record(lua_State* L, int idx) {
  return check_boxed<SimulationRecord>(L, idx, kSimulationMeta, "Simulation");
}

// The function at stack index `function`, given for option `option`,
// called at time t: its three results, which must be finite numbers
// (`quantity` names them and their unit in the error).
Vec3 call_time_function(lua_State* L, int function, int arg, double t, const char* option, const char* quantity) {
  lua_pushvalue(L, function);
  lua_pushnumber(L, t);
  protected_call(L, 1, 3);
  Vec3 a;
  for (int k = 0; k < 3; ++k) {
    const int idx = lua_gettop(L) - 2 + k;
    if (lua_type(L, idx) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, idx))) {
      const std::string got = lua_type(L, idx) == LUA_TNUMBER ? number_text(lua_tonumber(L, idx)) : type_name(L, idx);
      lua_pop(L, 3);
      throw ArgError(arg, std::string(option) + ": the function must return three finite numbers " + quantity +
                              "; at t = " + number_text(t) + " its result " + std::to_string(k + 1) + " is " + got);
    }
    a[k] = lua_tonumber(L, idx);
  }
  lua_pop(L, 3);
  return a;
}

int w_Simulation_trajectory(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
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
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
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
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
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

void push_block_numbers(lua_State* L, const std::vector<double>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

int w_Simulation_summary(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
    const OptionTable options(L, 2, {"moved_fraction", "fall_fraction", "fall_level"});
    SummaryOptions o;
    o.moved_fraction = options.positive("moved_fraction", record->moved_fraction);
    o.fall_fraction = options.positive("fall_fraction", o.fall_fraction);
    o.fall_level = options.number("fall_level");
    const SimulationSummary summary = summarize(record->structure, record->result, o);
    const bool verdict = record->result.status == SimulationStatus::completed;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 12);
      set_field(L, "peak_displacement", summary.peak);
      set_field(L, "residual_displacement", summary.residual);
      if (summary.peak_block >= 0) set_index_field(L, "peak_block", summary.peak_block);
      if (summary.residual_block >= 0) set_index_field(L, "residual_block", summary.residual_block);
      push_block_numbers(L, summary.peak_displacement);
      lua_setfield(L, -2, "peak_displacements");
      push_block_numbers(L, summary.residual_displacement);
      lua_setfield(L, -2, "residual_displacements");
      if (summary.first_movement) set_field(L, "first_movement", *summary.first_movement);
      if (verdict) set_boolean(L, "collapsed", summary.collapse_time.has_value());
      if (summary.collapse_time) set_field(L, "collapse_time", *summary.collapse_time);
      lua_createtable(L, static_cast<int>(summary.fallen.size()), 0);
      for (size_t k = 0; k < summary.fallen.size(); ++k) {
        lua_pushinteger(L, summary.fallen[k] + 1);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "fallen");
      push_block_numbers(L, summary.fall_times);
      lua_setfield(L, -2, "fall_times");
      return 1;
    });
  });
}

int w_Simulation_drift(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
    const std::vector<int> blocks = check_block_list(L, record->structure, 2, 2, "blocks");
    const Drift d = drift(record->structure, record->result, blocks);
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 5);
      set_field(L, "height", d.height);
      set_field(L, "peak", d.peak);
      set_field(L, "residual", d.residual);
      push_block_numbers(L, record->result.times);
      lua_setfield(L, -2, "times");
      push_block_numbers(L, d.values);
      lua_setfield(L, -2, "values");
      return 1;
    });
  });
}

// The blocks a chart shows by default: the free blocks of largest peak
// displacement, at most this many.
constexpr std::size_t kChartedBlocks = 5;

int w_Simulation_chart(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
    const Structure& s = record->structure;
    const SimulationResult& r = record->result;
    const OptionTable options(L, 2, {"path", "blocks", "quantity", "title", "width", "height"});
    const std::optional<std::string> given = options.string("path");
    if (!given) throw ArgError(2, "path: required, the file to write (.png, .svg or .pdf)");
    const std::string path = sandbox::require_access(L, 2, "path", *given, sandbox::Access::write);
    const std::string quantity = options.string("quantity").value_or("displacement");
    if (quantity != "displacement" && quantity != "drift") {
      throw ArgError(2, "quantity: expected \"displacement\" or \"drift\", got \"" + quantity + "\"");
    }
    std::vector<int> blocks;
    if (options.push("blocks") != LUA_TNIL) {
      blocks = check_block_list(L, s, -1, 2, "blocks");
    } else {
      for (int i = 0; i < static_cast<int>(s.size()); ++i) {
        if (!s.is_support(i)) blocks.push_back(i);
      }
      std::stable_sort(blocks.begin(), blocks.end(), [&](int a, int b) { return r.displacement[a] > r.displacement[b]; });
      if (quantity == "displacement" && blocks.size() > kChartedBlocks) blocks.resize(kChartedBlocks);
    }
    lua_pop(L, 1);
    const auto label = [&](int i) { return s.name(i).empty() ? "block " + std::to_string(i + 1) : s.name(i); };
    ChartSpec spec;
    spec.kind = ChartKind::lines;
    spec.title = options.string("title").value_or("");
    spec.x_label = "time (s)";
    spec.width = image_size(options, "width", spec.width);
    spec.height = image_size(options, "height", spec.height);
    const auto series_of = [&](std::string name, const std::vector<double>& values) {
      ChartSeries line{std::move(name), {}};
      for (size_t k = 0; k < values.size(); ++k) line.points.emplace_back(r.times[k], values[k]);
      return line;
    };
    if (quantity == "drift") {
      spec.y_label = "drift";
      const Drift d = drift(s, r, blocks);
      std::string name = blocks.size() == 1 ? label(blocks[0]) : std::to_string(blocks.size()) + " blocks";
      spec.series.push_back(series_of("drift of " + name, d.values));
    } else {
      spec.y_label = "displacement (m)";
      for (const int i : blocks) {
        if (s.is_support(i)) throw ArgError(2, "blocks: block " + std::to_string(i + 1) + " is a support, which does not move");
        spec.series.push_back(series_of(label(i), displacement_history(s, r, i)));
      }
    }
    draw_chart(path, spec);
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 2);
      set_string(L, "path", path.c_str());
      lua_createtable(L, static_cast<int>(spec.series.size()), 0);
      for (size_t k = 0; k < spec.series.size(); ++k) {
        lua_createtable(L, 0, 2);
        set_string(L, "name", spec.series[k].name.c_str());
        set_field(L, "points", static_cast<int>(spec.series[k].points.size()));
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "series");
      return 1;
    });
  });
}

int w_Simulation_index(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<SimulationRecord> record = check_simulation_record(L, 1);
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
      else if (is("summary")) lua_pushcfunction(L, w_Simulation_summary);
      else if (is("drift")) lua_pushcfunction(L, w_Simulation_drift);
      else if (is("chart")) lua_pushcfunction(L, w_Simulation_chart);
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
      else if (is("split_steps")) lua_pushinteger(L, r.split_steps);
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
    const SimulationResult& r = check_simulation_record(L, 1)->result;
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
    luax_pushSimulation(L, *structure, std::move(result), settings.moved_fraction);
    return 1;
  });
}

constexpr const char* kAxisNames[] = {"x", "y", "z"};

// An axis name "x", "y" or "z" at stack index idx: its unit vector.
Vec3 axis_direction(lua_State* L, int idx, int arg, const std::string& what) {
  if (lua_type(L, idx) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, idx);
    for (int k = 0; k < 3; ++k) {
      if (name == kAxisNames[k]) return Vec3::Unit(k);
    }
  }
  const std::string got = lua_type(L, idx) == LUA_TSTRING ? "\"" + std::string(lua_tostring(L, idx)) + "\""
                                                           : type_name(L, idx);
  throw ArgError(arg, what + ": expected an axis \"x\", \"y\" or \"z\", got " + got);
}

// The components of one file: its columns along `directions` (one per
// column; none given: along x, y, z in turn).
void add_file_components(const std::string& path, std::vector<Vec3> directions, bool at2,
                         std::optional<AccelerationUnit> unit, double scale, Baseline baseline,
                         std::vector<GroundMotion::Component>& components) {
  const RecordColumns record = at2 ? read_at2(path) : read_acceleration_table(path);
  if (directions.empty()) {
    for (size_t c = 0; c < record.columns.size(); ++c) directions.push_back(Vec3::Unit(static_cast<int>(c)));
  }
  if (directions.size() != record.columns.size()) {
    throw ArgError(1, "component: \"" + path + "\" has " + std::to_string(record.columns.size()) +
                          " acceleration column(s) but component names " + std::to_string(directions.size()) +
                          " axis(es): give one axis per column");
  }
  for (size_t c = 0; c < directions.size(); ++c) {
    components.push_back(record_component(record, static_cast<int>(c), unit.value_or(AccelerationUnit::g), scale,
                                          baseline, directions[c]));
  }
}

int w_ground_motion(lua_State* L) {
  return guard(L, [&] {
    if (lua_type(L, 1) != LUA_TTABLE) {
      throw ArgError(1, "expected an option table {path = \"record.at2\" | \"record.csv\", ...}, got " +
                            type_name(L, 1));
    }
    const OptionTable options(L, 1, {"path", "format", "units", "scale", "component", "baseline"});
    const double scale = options.number("scale", 1.0);
    const std::optional<AccelerationUnit> unit = options.choice("units", kAccelerationUnitNames);
    const Baseline baseline = options.choice("baseline", kBaselineNames).value_or(Baseline::none);
    const std::optional<std::string> format = options.string("format");
    if (format && *format != "at2" && *format != "table") {
      throw ArgError(1, "format: expected \"at2\" (PEER NGA) or \"table\" (time and accelerations), got \"" +
                            *format + "\"");
    }
    // (path, axes) per file: `path` a string with `component`, or {x = path, y = path, z = path}.
    std::vector<std::pair<std::string, std::vector<Vec3>>> files;
    const int path_type = options.push("path");
    const int path_index = lua_gettop(L);
    if (path_type == LUA_TSTRING) {
      const std::string path = sandbox::checked_path(L, path_index, "path", sandbox::Access::read);
      std::vector<Vec3> axes;
      const int component_type = options.push("component");
      if (component_type == LUA_TTABLE) {
        const lua_Unsigned count = lua_rawlen(L, -1);
        for (lua_Unsigned k = 1; k <= count; ++k) {
          lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
          axes.push_back(axis_direction(L, lua_gettop(L), 1, "component[" + std::to_string(k) + "]"));
          lua_pop(L, 1);
        }
      } else if (component_type != LUA_TNIL) {
        axes.push_back(axis_direction(L, lua_gettop(L), 1, "component"));
      }
      lua_pop(L, 1);
      files.emplace_back(path, axes);
    } else if (path_type == LUA_TTABLE) {
      if (options.has("component")) {
        throw ArgError(1, "component: path = {x = ..., y = ..., z = ...} names the axis of each file already");
      }
      lua_pushnil(L);
      while (lua_next(L, path_index) != 0) {
        const std::string key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "";
        lua_pushvalue(L, -2);
        const Vec3 axis = axis_direction(L, lua_gettop(L), 1, "path's key");
        lua_pop(L, 1);
        if (lua_type(L, -1) != LUA_TSTRING) {
          throw ArgError(1, "path." + key + ": expected a file name, got " + type_name(L, -1));
        }
        const std::string what = "path." + key;
        files.emplace_back(sandbox::checked_path(L, lua_gettop(L), what.c_str(), sandbox::Access::read),
                           std::vector<Vec3>{axis});
        lua_pop(L, 1);
      }
      if (files.empty()) throw ArgError(1, "path: expected a file, or {x = file, y = file, z = file}, got an empty table");
      // Key order is Lua's; keep x, y, z.
      std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) {
        return a.second[0].dot(Vec3(0, 1, 2)) < b.second[0].dot(Vec3(0, 1, 2));
      });
    } else {
      throw ArgError(1, "path: required, a file (.at2, or a table of time and acceleration such as .csv) or "
                        "{x = file, y = file, z = file}, got " + type_name(L, -1));
    }
    lua_pop(L, 1);
    std::vector<GroundMotion::Component> components;
    for (const auto& [path, given_axes] : files) {
      const bool at2 = format ? *format == "at2" : file_extension(path) == "at2";
      if (at2 && unit) {
        throw ArgError(1, "units: an AT2 file states its units in its header (\"" + path +
                              "\"); units applies to tables");
      }
      if (!at2 && !unit) {
        throw ArgError(1, "units: required for a table (\"" + path +
                              "\" does not state its units): \"g\", \"m/s2\" or \"cm/s2\"");
      }
      add_file_components(path, given_axes, at2, unit, scale, baseline, components);
    }
    auto motion = std::make_shared<GroundMotion>(std::move(components));
    push_boxed(L, std::move(motion), kGroundMotionMeta);
    return 1;
  });
}

int w_GroundMotion_call(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<GroundMotion> motion = check_ground_motion(L, 1);
    const Vec3 a = (*motion)(check_number(L, 2, "t"));
    for (int k = 0; k < 3; ++k) lua_pushnumber(L, a[k]);
    return 3;
  });
}

int w_GroundMotion_index(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<GroundMotion> motion = check_ground_motion(L, 1);
    const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : nullptr;
    if (!key) return 0;
    const std::string name = key;
    if (name == "duration") lua_pushnumber(L, motion->duration());
    else if (name == "peak") lua_pushnumber(L, motion->peak());
    else if (name == "peak_time") lua_pushnumber(L, motion->peak_time());
    else if (name == "components") lua_pushinteger(L, static_cast<lua_Integer>(motion->components().size()));
    else if (name == "samples") lua_pushinteger(L, static_cast<lua_Integer>(motion->components().front().times.size()));
    else return 0;
    return 1;
  });
}

int w_GroundMotion_tostring(lua_State* L) {
  if (push_if_closed<GroundMotion>(L, kGroundMotionMeta, "GroundMotion")) return 1;
  return guard(L, [&] {
    const std::shared_ptr<GroundMotion> motion = check_ground_motion(L, 1);
    return push_string(L, "GroundMotion (" + std::to_string(motion->components().size()) + " component(s), " +
                              message_number(motion->duration()) + " s, peak " + message_number(motion->peak()) +
                              " m/s^2 at " + message_number(motion->peak_time()) + " s)");
  });
}

int w_GroundMotion_gc(lua_State* L) { return release_boxed<GroundMotion>(L, kGroundMotionMeta); }

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
  o.threads = static_cast<int>(
      options.whole("threads", 0, 1024, "a whole number from 0 (one per core) to 1024").value_or(o.threads));
  // ground_acceleration and ground_rotation: a GroundMotion, or a function
  // that stays on the stack for the run.
  const auto time_function = [&](const char* option, const char* quantity) -> std::function<Vec3(double)> {
    const int type = options.push(option);
    if (type == LUA_TUSERDATA && test_boxed<GroundMotion>(L, -1, kGroundMotionMeta)) {
      std::shared_ptr<const GroundMotion> motion = check_ground_motion(L, lua_gettop(L));
      lua_pop(L, 1);
      return [motion](double t) { return (*motion)(t); };
    }
    if (type == LUA_TFUNCTION) {
      const int function = lua_gettop(L);
      return [L, function, arg, option, quantity](double t) {
        return call_time_function(L, function, arg, t, option, quantity);
      };
    }
    if (type != LUA_TNIL) {
      throw ArgError(arg, std::string(option) + ": expected a GroundMotion (ashlar.ground_motion) or a function(t) " +
                              "returning " + quantity + ", got " + type_name(L, -1));
    }
    lua_pop(L, 1);
    return nullptr;
  };
  o.ground_acceleration = time_function("ground_acceleration", "ax, ay, az (m/s^2)");
  o.ground_rotation = time_function("ground_rotation", "rx, ry, rz (rad, a rotation vector)");
  if (const std::optional<Vec3> pivot = options.vec3("ground_pivot")) o.ground_pivot = *pivot;
  if (options.boolean("progress").value_or(false)) {
    const auto steps = static_cast<std::size_t>(std::ceil(o.duration / o.step - 1e-9));
    const double step = o.step;
    progress = std::make_shared<SimulationProgress>(std::to_string(structure.size()) + " blocks", steps);
    SimulationProgress* line = progress.get();
    o.progress = [line, step](double t) { line->update(static_cast<std::size_t>(std::lround(t / step))); };
  }
  return o;
}

void luax_pushSimulation(lua_State* L, const Structure& structure, SimulationResult result, double moved_fraction) {
  auto record = std::make_shared<SimulationRecord>(SimulationRecord{structure, std::move(result), moved_fraction});
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
  // Callable, so that it serves wherever a function(t) returning ax, ay, az does.
  static const luaL_Reg motion_metamethods[] = {{"__index", w_GroundMotion_index},
                                                {"__call", w_GroundMotion_call},
                                                {"__tostring", w_GroundMotion_tostring},
                                                {"__gc", w_GroundMotion_gc},
                                                {"__close", w_GroundMotion_gc},
                                                {nullptr, nullptr}};
  register_type(L, kGroundMotionMeta, nullptr, motion_metamethods);
}

void set_simulation_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"simulate", w_simulate}, {"ground_motion", w_ground_motion}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
