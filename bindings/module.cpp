// The `ashlar` C module for a stock lua5.4: `require "ashlar"` with the built
// ashlar.so on package.cpath.
#include "ashlar_lua.hpp"

extern "C" __attribute__((visibility("default"))) int luaopen_ashlar(lua_State* L) {
  ashlar_add_model_path(L);
  return ashlar_open_library(L);
}
