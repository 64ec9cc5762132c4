// Lua type "ashlar.Structure": blocks, supports, loads and their contacts.
#pragma once

#include <lua.hpp>
#include <memory>

#include "luax.hpp"
#include "structure/structure.hpp"

namespace ashlar::lua {

// The structure at stack index idx, for the caller to keep while it uses it
// (see check_boxed); throws ArgError unless it is an open Structure.
std::shared_ptr<Structure> luax_checkStructure(lua_State* L, int idx);
void luax_pushStructure(lua_State* L, std::shared_ptr<Structure> structure);
void register_Structure(lua_State* L);
// ashlar.structure and ashlar.load: set into the table on top of the stack.
void set_structure_functions(lua_State* L);

// Contact options from an option table's keys for the tolerance (m), the
// angle (rad) and the smallest interface area (m^2); absent keys keep the
// defaults.
ContactOptions contact_options(const OptionTable& options, const char* tolerance_key, const char* angle_key,
                               const char* min_width_key,
                               const char* min_area_key);

// Block index argument: an integer 1..#s or a block name; returns 0-based.
int check_block_index(lua_State* L, const Structure& s, int idx, int arg, const char* what);

// A block (index or name) or a list of them at stack index idx; 0-based. An
// empty list is an error unless `allow_empty`.
std::vector<int> check_block_list(lua_State* L, const Structure& s, int idx, int arg, const char* what,
                                  bool allow_empty = false);

}  // namespace ashlar::lua
