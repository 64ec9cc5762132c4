// Lua type "ashlar.Block": an immutable block shared by structures.
#pragma once

#include <lua.hpp>

#include "geometry/block.hpp"

namespace ashlar::lua {

// The block at stack index idx, for the caller to keep while it uses it (see
// check_boxed); throws ArgError unless it is an open Block.
BlockPtr luax_checkBlock(lua_State* L, int idx);
void luax_pushBlock(lua_State* L, BlockPtr block);
// Registers the metatable; called once when the library opens.
void register_Block(lua_State* L);
// ashlar.block, box, hull, prism, loft: set into the table on top of the stack.
void set_block_constructors(lua_State* L);

}  // namespace ashlar::lua
