#include "wrap_Structure.hpp"

#include <cmath>
#include <sstream>

#include "io/structure_json.hpp"
#include "structure/tolerance_sweep.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_Block.hpp"

namespace ashlar::lua {

ContactOptions contact_options(const OptionTable& options, const char* tolerance_key, const char* angle_key,
                               const char* min_width_key, const char* min_area_key) {
  ContactOptions contact;
  if (tolerance_key) contact.tolerance = options.positive(tolerance_key, 0.0, true);
  if (const std::optional<double> angle = options.number(angle_key)) {
    if (!(*angle > 0.0 && *angle < 0.5 * M_PI)) {
      throw ArgError(options.arg(), std::string(angle_key) + ": expected an angle in radians between 0 and pi/2, got " +
                                        number_text(*angle));
    }
    contact.angle = *angle;
  }
  if (min_width_key) contact.min_width = options.positive(min_width_key, 0.0, true);
  if (min_area_key) contact.min_area = options.positive(min_area_key, 0.0, true);
  return contact;
}

namespace {

constexpr const char* kStructureMeta = "ashlar.Structure";

void push_interface(lua_State* L, const Interface& contact) {
  lua_createtable(L, 0, 11);
  set_index_field(L, "a", contact.a);
  set_index_field(L, "b", contact.b);
  set_field(L, "area", contact.area);
  set_field(L, "center", contact.center);
  set_field(L, "normal", contact.normal);
  set_field(L, "u", contact.u);
  set_field(L, "v", contact.v);
  lua_pushboolean(L, contact.is_explicit);
  lua_setfield(L, -2, "explicit");
  lua_pushboolean(L, contact.on_mid_plane);
  lua_setfield(L, -2, "mid_plane");
  push_points(L, contact.vertices);
  lua_setfield(L, -2, "vertices");
  lua_createtable(L, static_cast<int>(contact.holes.size()), 0);
  for (size_t h = 0; h < contact.holes.size(); ++h) {
    push_points(L, contact.holes[h]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(h + 1));
  }
  lua_setfield(L, -2, "holes");
}

int w_structure(lua_State* L) {
  return guard(L, [&] {
    if (!lua_isnoneornil(L, 1)) {
      throw ArgError(1, "ashlar.structure() takes no arguments; add blocks with s:add(block)");
    }
    luax_pushStructure(L, std::make_shared<Structure>());
    return 1;
  });
}

int w_load(lua_State* L) {
  return guard(L, [&] {
    const std::string path = sandbox::checked_path(L, 1, "path", sandbox::Access::read);
    const OptionTable options(L, 2, {"planarity"});
    const double planarity = options.positive("planarity", 0.0, /*zero_allowed=*/true);
    luax_pushStructure(L, std::make_shared<Structure>(load_structure(path, planarity)));
    return 1;
  });
}

int w_Structure_add(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    const BlockPtr block = luax_checkBlock(L, 2);
    const OptionTable options(L, 3, {"support", "name"});
    const int index =
        s.add(block, options.boolean("support").value_or(false), options.string("name").value_or(""));
    lua_pushinteger(L, index + 1);
    return 1;
  });
}

int w_Structure_add_load(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    const OptionTable options(L, 2, {"block", "force", "at"});
    if (lua_type(L, 2) != LUA_TTABLE) {
      throw ArgError(2, "expected a load table {block = i, force = {fx, fy, fz}, at = {x, y, z}}");
    }
    PointLoad load;
    options.push("block");
    load.block = check_block_index(L, s, -1, 2, "block");
    lua_pop(L, 1);
    const std::optional<Vec3> force = options.vec3("force");
    if (!force) throw ArgError(2, "force: required, a table of 3 numbers {fx, fy, fz} (N)");
    load.force = *force;
    load.at = options.vec3("at").value_or(s.block(load.block).centroid());
    s.add_load(load);
    lua_pushinteger(L, static_cast<lua_Integer>(s.loads().size()));
    return 1;
  });
}

// One end of s:add_cable's table: {block = i or name, point = {x, y, z}};
// without a block the end is a junction with other cables' ends.
CableEnd cable_end(lua_State* L, const Structure& s, const OptionTable& options, const char* key) {
  const std::string what = key;
  if (options.push(key) != LUA_TTABLE) {
    throw ArgError(options.arg(), what + ": required, a table {block = i, point = {x, y, z}} "
                                         "(leave out block where cables meet), got " +
                                      type_name(L, -1));
  }
  const OptionTable end(L, lua_gettop(L), options.arg(), what + ".", {"block", "point"});
  CableEnd out;
  if (end.push("block") != LUA_TNIL) {
    out.block = check_block_index(L, s, -1, options.arg(), (what + ".block").c_str());
  }
  lua_pop(L, 1);
  const std::optional<Vec3> point = end.vec3("point");
  if (!point) throw ArgError(options.arg(), what + ".point: required, a table of 3 numbers (m)");
  out.point = *point;
  lua_pop(L, 1);
  return out;
}

int w_Structure_add_cable(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    if (lua_type(L, 2) != LUA_TTABLE) {
      throw ArgError(2, "expected a cable table {from = {block = i, point = {..}}, to = {..}, "
                        "mass_per_length = 0, max_tension = nil}");
    }
    const OptionTable options(L, 2, {"from", "to", "mass_per_length", "max_tension"});
    Cable cable;
    cable.from = cable_end(L, s, options, "from");
    cable.to = cable_end(L, s, options, "to");
    cable.mass_per_length = options.positive("mass_per_length", 0.0, true);
    if (options.has("max_tension")) {
      cable.max_tension = options.positive("max_tension", cable.max_tension);
    }
    lua_pushinteger(L, s.add_cable(cable) + 1);
    return 1;
  });
}

int w_Structure_add_interface(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    if (lua_type(L, 2) != LUA_TTABLE) {
      throw ArgError(2, "expected an interface table {a = i, b = j, polygons = {{{x, y, z}, ...}, ...}, "
                        "normal = nil}, got " + type_name(L, 2));
    }
    const OptionTable options(L, 2, {"a", "b", "polygons", "normal"});
    int ends[2];
    const char* keys[2] = {"a", "b"};
    for (int k = 0; k < 2; ++k) {
      options.push(keys[k]);
      ends[k] = check_block_index(L, s, -1, 2, keys[k]);
      lua_pop(L, 1);
    }
    if (options.push("polygons") != LUA_TTABLE) {
      throw ArgError(2, "polygons: required, a list of polygons {{{x, y, z}, ...}, ...} (m), got " + type_name(L, -1));
    }
    const int list = lua_gettop(L);
    std::vector<std::vector<Vec3>> polygons;
    const lua_Unsigned count = lua_rawlen(L, list);
    for (lua_Unsigned k = 1; k <= count; ++k) {
      lua_rawgeti(L, list, static_cast<lua_Integer>(k));
      if (lua_type(L, -1) == LUA_TTABLE && lua_rawgeti(L, -1, 1) == LUA_TNUMBER) {
        throw ArgError(2, "polygons: expected a list of polygons, got a list of points (wrap the polygon in "
                          "another table: polygons = {{{x, y, z}, ...}})");
      }
      lua_settop(L, list + 1);  // the polygon
      polygons.push_back(to_points(L, -1, 2, "polygons[" + std::to_string(k) + "]"));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    const std::optional<Vec3> normal = options.vec3("normal");
    lua_pushinteger(L, s.add_interface(ends[0], ends[1], polygons, normal));
    return 1;
  });
}

int w_Structure_remove(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    luax_pushBlock(L, s.remove(check_block_index(L, s, 2, 2, "block")).block);
    return 1;
  });
}

int w_Structure_cables(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(s.cables().size()), 0);
      for (size_t c = 0; c < s.cables().size(); ++c) {
        const Cable& cable = s.cables()[c];
        lua_createtable(L, 0, 4);
        const std::pair<const CableEnd*, const char*> ends[2] = {{&cable.from, "from"},
                                                                 {&cable.to, "to"}};
        for (const auto& [end, key] : ends) {
          lua_createtable(L, 0, 2);
          if (end->block >= 0) set_index_field(L, "block", end->block);
          set_field(L, "point", end->point);
          lua_setfield(L, -2, key);
        }
        set_field(L, "mass_per_length", cable.mass_per_length);
        if (std::isfinite(cable.max_tension)) set_field(L, "max_tension", cable.max_tension);
        set_field(L, "length", (cable.to.point - cable.from.point).norm());
        lua_rawseti(L, -2, static_cast<lua_Integer>(c + 1));
      }
      return 1;
    });
  });
}

int w_Structure_len(lua_State* L) {
  return guard(L, [&] {
    lua_pushinteger(L, luax_checkStructure(L, 1)->size());
    return 1;
  });
}

int w_Structure_block(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    luax_pushBlock(L, s.entry(check_block_index(L, s, 2, 2, "block")).block);
    return 1;
  });
}

int w_Structure_name(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    return push_string(L, s.name(check_block_index(L, s, 2, 2, "block")));
  });
}

int w_Structure_is_support(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    lua_pushboolean(L, s.is_support(check_block_index(L, s, 2, 2, "block")));
    return 1;
  });
}

int w_Structure_find(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const int index = s.find(check_string(L, 2, "name"));
    if (index < 0) lua_pushnil(L);
    else lua_pushinteger(L, index + 1);
    return 1;
  });
}

int w_Structure_loads(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(s.loads().size()), 0);
      for (size_t i = 0; i < s.loads().size(); ++i) {
        const PointLoad& load = s.loads()[i];
        lua_createtable(L, 0, 3);
        set_index_field(L, "block", load.block);
        set_field(L, "force", load.force);
        set_field(L, "at", load.at);
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
      }
      return 1;
    });
  });
}

int w_Structure_bounds(lua_State* L) {
  return guard(L, [&] {
    const Box3 box = luax_checkStructure(L, 1)->bounds();
    if (box.empty()) return 0;
    return call_protected(L, 0, [&](lua_State* L) {
      push_vec3(L, box.lo);
      push_vec3(L, box.hi);
      return 2;
    });
  });
}

int w_Structure_interfaces(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {"tolerance", "angle", "min_width", "min_area"});
    const ContactOptions contact = contact_options(options, "tolerance", "angle", "min_width", "min_area");
    const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces(contact);
    const std::vector<Interface>& found = *found_list;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(found.size()), 0);
      for (size_t k = 0; k < found.size(); ++k) {
        push_interface(L, found[k]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      return 1;
    });
  });
}

// Pushes a list of { a = i, b = j, <field> = value } for pairs of blocks
// (0-based .a and .b, pushed 1-based), the value taken by value_of.
template <typename Pair, typename ValueOf>
void push_block_pairs(lua_State* L, const std::vector<Pair>& pairs, const char* field, ValueOf value_of) {
  lua_createtable(L, static_cast<int>(pairs.size()), 0);
  for (size_t k = 0; k < pairs.size(); ++k) {
    lua_createtable(L, 0, 3);
    set_index_field(L, "a", pairs[k].a);
    set_index_field(L, "b", pairs[k].b);
    set_field(L, field, value_of(pairs[k]));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

// Near misses: gaps a tolerance up to `range` times the current one would
// close, and overlaps deeper than the tolerance, which are errors.
int w_Structure_contact_report(lua_State* L) {
  return guard(L, [&] {
    const Structure& s = *luax_checkStructure(L, 1);
    const OptionTable options(L, 2, {"tolerance", "angle", "range"});
    const ContactOptions contact = contact_options(options, "tolerance", "angle", nullptr, nullptr);
    const double range = options.positive("range", 10.0);
    if (range <= 1.0) throw ArgError(2, "range: expected a number > 1 (a multiple of the tolerance), got " + number_text(range));
    const double tolerance = s.contact_tolerance(contact);
    const std::vector<NearMiss> gaps = s.near_misses(range * tolerance, contact);
    const std::shared_ptr<const std::vector<BlockOverlap>> overlaps_list = s.overlaps(contact);
    const std::vector<BlockOverlap>& overlaps = *overlaps_list;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 3);
      set_field(L, "tolerance", tolerance);
      push_block_pairs(L, gaps, "gap", [](const NearMiss& gap) { return gap.tolerance; });
      lua_setfield(L, -2, "gaps");
      push_block_pairs(L, overlaps, "depth", [](const BlockOverlap& overlap) { return overlap.depth; });
      lua_setfield(L, -2, "overlaps");
      return 1;
    });
  });
}

int w_Structure_overlaps(lua_State* L) {
  return guard(L, [&] {
    const Structure& s = *luax_checkStructure(L, 1);
    const OptionTable options(L, 2, {"tolerance"});
    ContactOptions contact;
    contact.tolerance = options.positive("tolerance", 0.0, true);
    const std::shared_ptr<const std::vector<BlockOverlap>> overlaps_list = s.overlaps(contact);
    const std::vector<BlockOverlap>& overlaps = *overlaps_list;
    return call_protected(L, 0, [&](lua_State* L) {
      push_block_pairs(L, overlaps, "depth", [](const BlockOverlap& overlap) { return overlap.depth; });
      return 1;
    });
  });
}

int w_Structure_set_planar(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    Structure& s = *structure;
    if (!lua_isboolean(L, 2)) {
      throw ArgError(2, "planar: expected true or false, got " + type_name(L, 2));
    }
    s.set_planar(lua_toboolean(L, 2));
    return 0;
  });
}

int w_Structure_is_planar(lua_State* L) {
  return guard(L, [&] {
    lua_pushboolean(L, luax_checkStructure(L, 1)->planar());
    return 1;
  });
}

int w_Structure_save(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    save_structure(s, sandbox::checked_path(L, 2, "path", sandbox::Access::write));
    return 0;
  });
}

int w_Structure_tostring(lua_State* L) {
  if (push_if_closed<Structure>(L, kStructureMeta, "Structure")) return 1;
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    int supports = 0;
    for (const StructureBlock& entry : s.entries()) supports += entry.support ? 1 : 0;
    std::ostringstream text;
    text << "Structure (" << s.size() << " blocks, " << supports << " supports, "
         << s.loads().size() << " loads)";
    return push_string(L, text.str());
  });
}

int w_Structure_gc(lua_State* L) { return release_boxed<Structure>(L, kStructureMeta); }

}  // namespace

int check_block_index(lua_State* L, const Structure& s, int idx, int arg, const char* what) {
  if (lua_type(L, idx) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, idx);
    const int index = s.find(name);
    if (index < 0) throw ArgError(arg, std::string(what) + ": no block is named '" + name + "'");
    return index;
  }
  int is_integer = 0;
  const lua_Integer index = lua_tointegerx(L, idx, &is_integer);
  if (lua_type(L, idx) != LUA_TNUMBER || !is_integer) {
    throw ArgError(arg, std::string(what) + ": expected a block index or name, got " +
                            type_name(L, idx));
  }
  if (index < 1 || index > s.size()) {
    throw ArgError(arg, std::string(what) + ": index " + std::to_string(index) +
                            " is out of range (the structure has " + std::to_string(s.size()) +
                            " blocks)");
  }
  return static_cast<int>(index - 1);
}

std::vector<int> check_block_list(lua_State* L, const Structure& s, int idx, int arg, const char* what,
                                  bool allow_empty) {
  idx = lua_absindex(L, idx);
  std::vector<int> blocks;
  if (lua_type(L, idx) != LUA_TTABLE) {
    blocks.push_back(check_block_index(L, s, idx, arg, what));
    return blocks;
  }
  const lua_Integer count = luaL_len(L, idx);
  if (count == 0 && !allow_empty) {
    throw ArgError(arg, std::string(what) + ": expected a block or a list of blocks, got an empty table");
  }
  for (lua_Integer k = 1; k <= count; ++k) {
    lua_geti(L, idx, k);
    const std::string item = std::string(what) + "[" + std::to_string(k) + "]";
    blocks.push_back(check_block_index(L, s, -1, arg, item.c_str()));
    lua_pop(L, 1);
  }
  return blocks;
}

std::shared_ptr<Structure> luax_checkStructure(lua_State* L, int idx) {
  return check_boxed<Structure>(L, idx, kStructureMeta, "Structure");
}

void luax_pushStructure(lua_State* L, std::shared_ptr<Structure> structure) {
  push_boxed<Structure>(L, std::move(structure), kStructureMeta);
}

void register_Structure(lua_State* L) {
  static const luaL_Reg methods[] = {{"add", w_Structure_add},
                                     {"add_load", w_Structure_add_load},
                                     {"add_cable", w_Structure_add_cable},
                                     {"add_interface", w_Structure_add_interface},
                                     {"remove", w_Structure_remove},
                                     {"cables", w_Structure_cables},
                                     {"block", w_Structure_block},
                                     {"name", w_Structure_name},
                                     {"is_support", w_Structure_is_support},
                                     {"find", w_Structure_find},
                                     {"loads", w_Structure_loads},
                                     {"bounds", w_Structure_bounds},
                                     {"interfaces", w_Structure_interfaces},
                                     {"overlaps", w_Structure_overlaps},
                                     {"contact_report", w_Structure_contact_report},
                                     {"set_planar", w_Structure_set_planar},
                                     {"is_planar", w_Structure_is_planar},
                                     {"save", w_Structure_save},
                                     {nullptr, nullptr}};
  static const luaL_Reg metamethods[] = {{"__len", w_Structure_len},
                                         {"__tostring", w_Structure_tostring},
                                         {"__gc", w_Structure_gc},
                                         {"__close", w_Structure_gc},
                                         {nullptr, nullptr}};
  register_type(L, kStructureMeta, methods, metamethods);
}

// ashlar.suggest_tolerance(s, { tolerances = {...}, angle, min_width, min_area }):
// the contacts at each candidate tolerance and the range where they do not
// change.
int w_suggest_tolerance(lua_State* L) {
  return guard(L, [&] {
    const Structure& s = *luax_checkStructure(L, 1);
    const OptionTable options(L, 2, {"tolerances", "angle", "min_width", "min_area"});
    const ContactOptions contact = contact_options(options, nullptr, "angle", "min_width", "min_area");
    std::vector<double> tolerances;
    const int type = options.push("tolerances");
    if (type == LUA_TTABLE) {
      const lua_Integer count = luaL_len(L, -1);
      for (lua_Integer k = 1; k <= count; ++k) {
        lua_rawgeti(L, -1, k);
        if (lua_type(L, -1) != LUA_TNUMBER) {
          throw ArgError(2, "tolerances[" + std::to_string(k) + "]: expected a number (m), got " + type_name(L, -1));
        }
        tolerances.push_back(lua_tonumber(L, -1));
        lua_pop(L, 1);
      }
    } else if (type != LUA_TNIL) {
      throw ArgError(2, "tolerances: expected a list of increasing numbers (m), got " + type_name(L, -1));
    }
    lua_pop(L, 1);
    if (tolerances.empty()) tolerances = default_sweep_tolerances(s);
    const ToleranceSweep sweep = sweep_contact_tolerance(s, contact, tolerances);
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 4);
      lua_createtable(L, static_cast<int>(sweep.rows.size()), 0);
      for (size_t k = 0; k < sweep.rows.size(); ++k) {
        const ToleranceRow& row = sweep.rows[k];
        lua_createtable(L, 0, 8);
        set_field(L, "tolerance", row.tolerance);
        set_field(L, "interfaces", row.interfaces);
        set_field(L, "pairs", row.pairs);
        set_field(L, "new_pairs", row.new_pairs);
        set_field(L, "lost_pairs", row.lost_pairs);
        set_field(L, "overlaps", row.overlaps);
        set_field(L, "floating", row.floating);
        set_field(L, "warped", row.warped);
        lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
      }
      lua_setfield(L, -2, "rows");
      if (sweep.suggested > 0.0) {
        set_field(L, "lo", sweep.lo);
        set_field(L, "hi", sweep.hi);
        set_field(L, "suggested", sweep.suggested);
      }
      return 1;
    });
  });
}

void set_structure_functions(lua_State* L) {
  static const luaL_Reg functions[] = {
      {"structure", w_structure}, {"load", w_load}, {"suggest_tolerance", w_suggest_tolerance}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
