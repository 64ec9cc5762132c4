// Entry points of the Lua bindings used by the host program and the C module.
#pragma once

#include <lua.hpp>

// Opens the `ashlar` library and returns its table (leaves it on the stack).
// The C module's luaopen_ashlar and the host's package.preload both call it.
int ashlar_open_library(lua_State* L);

// Appends the model library folder to package.path so that
// `require "ashlar.models"` works (idempotent). The folder is, in order:
// $ASHLAR_MODELS if set, else the source tree's models/ known at build time.
void ashlar_add_model_path(lua_State* L);
