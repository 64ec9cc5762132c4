#include "wrap_Block.hpp"

#include <sstream>

#include "geometry/block_builders.hpp"
#include "luax.hpp"

namespace ashlar::lua {

namespace {

constexpr const char* kBlockMeta = "ashlar.Block";

BlockStyle style_from(const OptionTable& options) {
  BlockStyle style;
  style.density = options.positive("density", kDefaultDensity);
  style.name = options.string("name").value_or("");
  style.planarity = options.positive("planarity", 0.0, /*zero_allowed=*/true);
  return style;
}

int push_new_block(lua_State* L, Block block) {
  luax_pushBlock(L, std::make_shared<const Block>(std::move(block)));
  return 1;
}

int w_block(lua_State* L) {
  return guard(L, [&] {
    const OptionTable options(L, 1, {"vertices", "faces", "density", "name", "planarity"});
    if (!options.has("vertices") || !options.has("faces")) {
      throw ArgError(1, "a block needs 'vertices' and 'faces'");
    }
    options.push("vertices");
    std::vector<Vec3> vertices = to_points(L, -1, 1, "vertices");
    options.push("faces");
    std::vector<FaceLoop> faces = to_faces(L, -1, 1, "faces");
    lua_pop(L, 2);
    const BlockStyle style = style_from(options);
    return push_new_block(
        L, Block(std::move(vertices), std::move(faces), style.density, style.name, style.planarity));
  });
}

int w_box(lua_State* L) {
  return guard(L, [&] {
    const OptionTable options(L, 1, {"size", "center", "density", "name"});
    const std::optional<Vec3> size = options.vec3("size");
    if (!size) throw ArgError(1, "size: required, a table of 3 positive numbers {sx, sy, sz}");
    return push_new_block(
        L, make_box(*size, options.vec3("center").value_or(Vec3::Zero()), style_from(options)));
  });
}

int w_hull(lua_State* L) {
  return guard(L, [&] {
    const std::vector<Vec3> points = to_points(L, 1, 1, "points");
    const OptionTable options(L, 2, {"density", "name"});
    return push_new_block(L, make_hull(points, style_from(options)));
  });
}

int w_prism(lua_State* L) {
  return guard(L, [&] {
    const std::vector<Vec3> polygon = to_points(L, 1, 1, "polygon");
    const Vec3 vector = to_vec3(L, 2, 2, "vector");
    const OptionTable options(L, 3, {"density", "name"});
    return push_new_block(L, make_prism(polygon, vector, style_from(options)));
  });
}

int w_loft(lua_State* L) {
  return guard(L, [&] {
    const std::vector<Vec3> polygon_a = to_points(L, 1, 1, "polygon_a");
    const std::vector<Vec3> polygon_b = to_points(L, 2, 2, "polygon_b");
    const OptionTable options(L, 3, {"density", "name"});
    return push_new_block(L, make_loft(polygon_a, polygon_b, style_from(options)));
  });
}

int w_Block_volume(lua_State* L) {
  return guard(L, [&] {
    lua_pushnumber(L, luax_checkBlock(L, 1)->volume());
    return 1;
  });
}

int w_Block_mass(lua_State* L) {
  return guard(L, [&] {
    lua_pushnumber(L, luax_checkBlock(L, 1)->mass());
    return 1;
  });
}

int w_Block_centroid(lua_State* L) {
  return guard(L, [&] {
    const Vec3 centroid = luax_checkBlock(L, 1)->centroid();
    return call_protected(L, 0, [&](lua_State* L) {
      push_vec3(L, centroid);
      return 1;
    });
  });
}

int w_Block_vertices(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    return call_protected(L, 0, [&](lua_State* L) {
      push_points(L, block->vertices());
      return 1;
    });
  });
}

int w_Block_faces(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    const std::vector<FaceLoop>& faces = block->faces();
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(faces.size()), 0);
      for (size_t f = 0; f < faces.size(); ++f) {
        lua_createtable(L, static_cast<int>(faces[f].size()), 0);
        for (size_t k = 0; k < faces[f].size(); ++k) {
          lua_pushinteger(L, faces[f][k] + 1);
          lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
        }
        lua_rawseti(L, -2, static_cast<lua_Integer>(f + 1));
      }
      return 1;
    });
  });
}

int w_Block_name(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    if (block->name().empty()) {
      lua_pushnil(L);
      return 1;
    }
    return push_string(L, block->name());
  });
}

int w_Block_density(lua_State* L) {
  return guard(L, [&] {
    lua_pushnumber(L, luax_checkBlock(L, 1)->density());
    return 1;
  });
}

int w_Block_planarity(lua_State* L) {
  return guard(L, [&] {
    lua_pushnumber(L, luax_checkBlock(L, 1)->planarity());
    return 1;
  });
}

int w_Block_warp(lua_State* L) {
  return guard(L, [&] {
    lua_pushnumber(L, luax_checkBlock(L, 1)->warp());
    return 1;
  });
}

int w_Block_bounds(lua_State* L) {
  return guard(L, [&] {
    const Box3 box = luax_checkBlock(L, 1)->bounds();
    return call_protected(L, 0, [&](lua_State* L) {
      push_vec3(L, box.lo);
      push_vec3(L, box.hi);
      return 2;
    });
  });
}

int w_Block_is_convex(lua_State* L) {
  return guard(L, [&] {
    lua_pushboolean(L, luax_checkBlock(L, 1)->convex());
    return 1;
  });
}

int w_Block_translated(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    return push_new_block(L, block->translated(to_vec3(L, 2, 2, "offset")));
  });
}

int w_Block_rotated(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    const Vec3 axis = to_vec3(L, 2, 2, "axis");
    const double angle = check_number(L, 3, "angle");
    const Vec3 origin = lua_isnoneornil(L, 4) ? Vec3::Zero() : to_vec3(L, 4, 4, "origin");
    return push_new_block(L, block->rotated(axis, angle, origin));
  });
}

int w_Block_with(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    const OptionTable options(L, 2, {"density", "name"});
    Block copy = *block;
    if (const std::optional<std::string> name = options.string("name")) {
      copy = copy.with_name(*name);
    }
    if (options.has("density")) copy = copy.with_density(options.positive("density", 0.0));
    return push_new_block(L, std::move(copy));
  });
}

int w_Block_split(lua_State* L) {
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    const Vec3 point = to_vec3(L, 2, 2, "point");
    const Vec3 normal = to_vec3(L, 3, 3, "normal");
    SplitResult parts = split_block(*block, point, normal);
    for (std::optional<Block>* part : {&parts.below, &parts.above}) {
      if (*part) push_new_block(L, std::move(**part));
      else lua_pushnil(L);
    }
    return 2;
  });
}

int w_Block_tostring(lua_State* L) {
  if (push_if_closed<const Block>(L, kBlockMeta, "Block")) return 1;
  return guard(L, [&] {
    const BlockPtr block = luax_checkBlock(L, 1);
    std::ostringstream text;
    text << "Block";
    if (!block->name().empty()) text << " '" << block->name() << "'";
    text << " (" << block->vertices().size() << " vertices, " << block->faces().size()
         << " faces, volume " << block->volume() << " m^3)";
    return push_string(L, text.str());
  });
}

int w_Block_gc(lua_State* L) { return release_boxed<const Block>(L, kBlockMeta); }

}  // namespace

BlockPtr luax_checkBlock(lua_State* L, int idx) {
  return check_boxed<const Block>(L, idx, kBlockMeta, "Block");
}

void luax_pushBlock(lua_State* L, BlockPtr block) {
  push_boxed<const Block>(L, std::move(block), kBlockMeta);
}

void register_Block(lua_State* L) {
  static const luaL_Reg methods[] = {
      {"volume", w_Block_volume},     {"mass", w_Block_mass},
      {"centroid", w_Block_centroid}, {"vertices", w_Block_vertices},
      {"faces", w_Block_faces},       {"name", w_Block_name},
      {"density", w_Block_density},   {"bounds", w_Block_bounds},
      {"is_convex", w_Block_is_convex}, {"translated", w_Block_translated},
      {"rotated", w_Block_rotated},   {"with", w_Block_with},
      {"split", w_Block_split},       {"planarity", w_Block_planarity},
      {"warp", w_Block_warp},         {nullptr, nullptr}};
  static const luaL_Reg metamethods[] = {{"__tostring", w_Block_tostring},
                                         {"__gc", w_Block_gc},
                                         {"__close", w_Block_gc},
                                         {nullptr, nullptr}};
  register_type(L, kBlockMeta, methods, metamethods);
}

void set_block_constructors(lua_State* L) {
  static const luaL_Reg constructors[] = {{"block", w_block}, {"box", w_box},
                                          {"hull", w_hull},   {"prism", w_prism},
                                          {"loft", w_loft},   {nullptr, nullptr}};
  luaL_setfuncs(L, constructors, 0);
}

}  // namespace ashlar::lua
