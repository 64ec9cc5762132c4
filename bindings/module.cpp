// The `ashlar` C module for a stock lua5.4: `require "ashlar"` with the built
// ashlar.so on package.cpath. `require "ashlar.models"` finds the same file
// (Lua's all-in-one C loader looks for luaopen_ashlar_models in ashlar.so),
// so the model library loads first too.
#include "ashlar_lua.hpp"

extern "C" __attribute__((visibility("default"))) int luaopen_ashlar(lua_State* L) {
  ashlar_add_model_path(L);
  return ashlar_open_library(L);
}

// The model library: with its folder on package.path, the Lua loader of
// "ashlar.models" found there (models/ashlar/models/init.lua).
extern "C" __attribute__((visibility("default"))) int luaopen_ashlar_models(lua_State* L) {
  ashlar_add_model_path(L);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchpath");
  lua_pushstring(L, "ashlar.models");
  lua_getfield(L, -3, "path");
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return luaL_error(L, "module 'ashlar.models' not found:%s", lua_tostring(L, -1));
  const char* file = lua_tostring(L, -2);
  if (luaL_loadfile(L, file) != LUA_OK) return lua_error(L);
  lua_pushstring(L, "ashlar.models");
  lua_pushstring(L, file);
  lua_call(L, 2, 1);
  return 1;
}
