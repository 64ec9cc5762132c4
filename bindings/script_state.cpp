#include "script_state.hpp"

#include <filesystem>
#include <new>
#include <system_error>

#include "ashlar_lua.hpp"

namespace ashlar::lua {

namespace {

const char* const kScriptKey = "ashlar.script";
const char* const kScriptMetatable = "ashlar.ScriptInvocation";

int release_invocation(lua_State* L) {
  if (auto* invocation = static_cast<ScriptInvocation*>(luaL_testudata(L, 1, kScriptMetatable))) {
    invocation->~ScriptInvocation();
    lua_pushnil(L);
    lua_setmetatable(L, 1);  // destroyed once, however often __gc runs
  }
  return 0;
}

}  // namespace

void set_up_state(lua_State* L, const char* script) {
  luaL_openlibs(L);
  // The same collector mode as stock lua5.4, so scripts time alike in both.
  lua_gc(L, LUA_GCGEN, 0, 0);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "preload");
  lua_pushcfunction(L, ashlar_open_library);
  lua_setfield(L, -2, "ashlar");
  lua_pop(L, 2);
  ashlar_add_model_path(L);
  if (script != nullptr) prepend_script_folder(L, script);
}

void prepend_script_folder(lua_State* L, const char* script) {
  namespace fs = std::filesystem;
  fs::path folder = fs::path(script).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ignored;  // a relative folder still works while the cwd stays
  const fs::path absolute = fs::absolute(folder, ignored);
  if (!absolute.empty()) folder = absolute.lexically_normal();
  std::string directory = folder.string();
  if (directory.size() > 1 && directory.back() == '/') directory.pop_back();

  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  const std::string path = directory + "/?.lua;" + directory + "/?/init.lua;" +
                           (lua_tostring(L, -1) ? lua_tostring(L, -1) : "");
  lua_pop(L, 1);
  lua_pushlstring(L, path.data(), path.size());
  lua_setfield(L, -2, "path");
  lua_pop(L, 1);
}

void create_arg_table(lua_State* L, const std::vector<std::string>& argv, int script) {
  const int argc = static_cast<int>(argv.size());
  if (script >= argc) script = 0;
  lua_createtable(L, argc - script - 1, script + 1);
  for (int i = 0; i < argc; ++i) {
    lua_pushstring(L, argv[static_cast<std::size_t>(i)].c_str());
    lua_rawseti(L, -2, i - script);
  }
  lua_setglobal(L, "arg");
}

void remember_script(lua_State* L, const ScriptInvocation& invocation) {
  void* memory = lua_newuserdatauv(L, sizeof(ScriptInvocation), 0);
  new (memory) ScriptInvocation(invocation);
  if (luaL_newmetatable(L, kScriptMetatable)) {
    lua_pushcfunction(L, release_invocation);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  lua_setfield(L, LUA_REGISTRYINDEX, kScriptKey);
}

const ScriptInvocation* remembered_script(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kScriptKey);
  auto* invocation = static_cast<ScriptInvocation*>(luaL_testudata(L, -1, kScriptMetatable));
  lua_pop(L, 1);
  return invocation;
}

}  // namespace ashlar::lua
