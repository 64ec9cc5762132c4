// ashlar.sandbox: runs an untrusted script in a sandboxed Lua state of its own
// and reports what became of it (see sandbox.hpp for what the state allows).
#include "wrap_sandbox.hpp"

#include <filesystem>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "host_state.hpp"
#include "luax.hpp"
#include "sandbox.hpp"

namespace ashlar::lua {

namespace {

struct SandboxRequest {
  std::string script;       // a file, as given (from the current folder), or
  std::string script_file;  // the same file, absolute (the base folder is the script's)
  std::string source;  // the chunk itself
  std::vector<std::string> args;
  std::vector<std::string> argv;  // the script's `arg`: "ashlar.sandbox", the script, args
  sandbox::Settings settings;
};

std::vector<std::string> string_list(const OptionTable& options, const char* key) {
  lua_State* L = options.state();
  std::vector<std::string> list;
  const int type = options.push(key);
  if (type == LUA_TSTRING) {
    list.emplace_back(lua_tostring(L, -1));
  } else if (type == LUA_TTABLE) {
    const lua_Unsigned count = lua_rawlen(L, -1);
    for (lua_Unsigned k = 1; k <= count; ++k) {
      lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
      if (lua_type(L, -1) != LUA_TSTRING && lua_type(L, -1) != LUA_TNUMBER)
        throw ArgError(options.arg(), std::string(key) + "[" + std::to_string(k) + "]: expected a string, got " +
                                          type_name(L, -1));
      // lua_tostring would convert a number in place, which allocates.
      list.push_back(lua_type(L, -1) == LUA_TNUMBER ? lua_number_text(L, -1) : lua_tostring(L, -1));
      lua_pop(L, 1);
    }
  } else if (type != LUA_TNIL) {
    throw ArgError(options.arg(), std::string(key) + ": expected a string or a list of strings, got " + type_name(L, -1));
  }
  lua_pop(L, 1);
  return list;
}

SandboxRequest read_request(lua_State* L) {
  const OptionTable options(L, 1, {"script", "source", "args", "read", "write", "memory", "instructions", "time"});
  if (lua_isnoneornil(L, 1))
    throw ArgError(1, "expected an option table {script = path or source = chunk, read = ..., write = ..., ...}");
  SandboxRequest request;
  if (options.has("script") == options.has("source"))
    throw ArgError(1, "give exactly one of script (a file) and source (a chunk)");
  request.script = options.string("script").value_or("");
  request.source = options.string("source").value_or("");
  if (options.has("script") && request.script.empty()) throw ArgError(1, "script: expected a file name, got ''");
  request.args = string_list(options, "args");
  request.argv = {"ashlar.sandbox", request.script.empty() ? "=(source)" : request.script};
  request.argv.insert(request.argv.end(), request.args.begin(), request.args.end());
  request.settings.read_folders = string_list(options, "read");
  request.settings.write_folders = string_list(options, "write");
  if (!request.script.empty()) {
    const std::filesystem::path folder = std::filesystem::path(request.script).parent_path();
    request.settings.base_folder = folder.string();
    request.script_file = std::filesystem::absolute(request.script).string();
    if (!options.has("read")) request.settings.read_folders.push_back(folder.empty() ? "." : folder.string());
  }
  constexpr lua_Integer kMostBytes = lua_Integer{1} << 50;
  request.settings.memory_bytes = static_cast<std::size_t>(
      options.whole("memory", 0, kMostBytes, "a whole number of bytes >= 0 (0: no limit)")
          .value_or(static_cast<lua_Integer>(request.settings.memory_bytes)));
  request.settings.instructions = static_cast<std::uint64_t>(
      options.whole("instructions", 0, LUA_MAXINTEGER, "a whole number >= 0 (0: no budget)").value_or(0));
  request.settings.seconds = options.positive("time", 0.0, /*zero_allowed=*/true);
  return request;
}

// Under lua_pcall in the sandboxed state, which may run out of memory at any
// call: sets it up like the host's and leaves the loaded chunk and its
// arguments on the stack. It reads the request and holds no C++ object.
int load_request(lua_State* S) {
  const auto& request = *static_cast<const SandboxRequest*>(lua_touserdata(S, 1));
  lua_settop(S, 0);
  host::create_arg_table(S, request.argv, 1);
  int status;
  if (request.script.empty()) {
    status = luaL_loadbufferx(S, request.source.data(), request.source.size(), "=(sandbox source)", "t");
  } else {
    host::prepend_script_folder_to_path(S, request.script.c_str());
    {
      const std::string problem = sandbox::access_problem(S, request.script_file, sandbox::Access::read);
      if (!problem.empty()) push_message(S, problem.c_str());  // or, without memory, that error
    }
    if (lua_gettop(S) > 0) return lua_error(S);
    status = luaL_loadfilex(S, request.script.c_str(), "t");
  }
  if (status != LUA_OK) return lua_error(S);
  luaL_checkstack(S, static_cast<int>(request.args.size()) + 1, "too many arguments to the script");
  for (const std::string& argument : request.args) lua_pushstring(S, argument.c_str());
  return lua_gettop(S);
}

// Numbers, strings, booleans and nils the script returned, copied across.
void push_results(lua_State* L, lua_State* S, int first, int last) {
  lua_createtable(L, last - first + 1, 0);
  for (int i = first; i <= last; ++i) {
    switch (lua_type(S, i)) {
      case LUA_TNUMBER:
        if (lua_isinteger(S, i))
          lua_pushinteger(L, lua_tointeger(S, i));
        else
          lua_pushnumber(L, lua_tonumber(S, i));
        break;
      case LUA_TSTRING: {
        std::size_t length = 0;
        const char* text = lua_tolstring(S, i, &length);
        lua_pushlstring(L, text, length);
        break;
      }
      case LUA_TBOOLEAN:
        lua_pushboolean(L, lua_toboolean(S, i));
        break;
      default:
        lua_pushnil(L);
        break;
    }
    lua_rawseti(L, -2, i - first + 1);
  }
}

const char* status_name(int status, const sandbox::Usage& usage) {
  if (status == LUA_OK) return "ok";
  if (usage.exceeded == sandbox::Limit::instructions || usage.exceeded == sandbox::Limit::time)
    return sandbox::limit_name(usage.exceeded);
  if (status == LUA_ERRMEM || (usage.exceeded == sandbox::Limit::memory && status != LUA_ERRSYNTAX))
    return "memory";
  return "error";
}

// Closes the sandboxed state however the call ends.
struct ClosedState {
  lua_State* S;
  ~ClosedState() { sandbox::close_state(S); }
};

int w_sandbox(lua_State* L) {
  return guard(L, [&] {
    if (sandbox::settings_of(L) != nullptr)
      throw Error("ashlar.sandbox is not allowed inside a sandbox");
    const SandboxRequest request = read_request(L);
    const Clock::time_point started = Clock::now();
    const ClosedState state{sandbox::new_state(request.settings)};
    lua_State* S = state.S;
    lua_pushcfunction(S, load_request);
    lua_pushlightuserdata(S, const_cast<SandboxRequest*>(&request));
    int status = lua_pcall(S, 1, LUA_MULTRET, 0);
    if (status == LUA_OK) status = host::call_with_traceback(S, lua_gettop(S) - 1, LUA_MULTRET);
    if (status == LUA_OK) {
      const std::string late = sandbox::deadline_problem(S);
      if (!late.empty()) {
        push_message(S, late.c_str());  // S is outside any pcall here: a plain push could not raise safely
        status = LUA_ERRRUN;
      }
    }
    const sandbox::Usage usage = sandbox::usage_of(S);
    const double seconds = seconds_since(started);
    std::string message;
    if (status != LUA_OK) {
      // Not lua_tostring on a number: it would convert it in S, unprotected.
      const int type = lua_type(S, -1);
      message = sandbox::explain_error(S, type == LUA_TSTRING   ? std::string(lua_tostring(S, -1))
                                          : type == LUA_TNUMBER ? lua_number_text(S, -1)
                                                                : "(error object is not a string)");
    }

    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 8);
      set_string(L, "status", status_name(status, usage));
      if (status == LUA_OK) {
        push_results(L, S, 1, lua_gettop(S));
      } else {
        set_string(L, "message", message.c_str());
        lua_newtable(L);
      }
      lua_setfield(L, -2, "results");
      lua_pushinteger(L, static_cast<lua_Integer>(usage.memory_peak_bytes));
      lua_setfield(L, -2, "memory_peak");
      lua_pushinteger(L, static_cast<lua_Integer>(usage.instructions));
      lua_setfield(L, -2, "instructions");
      set_field(L, "seconds", seconds);
      return 1;
    });
  });
}

}  // namespace

void set_sandbox_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"sandbox", w_sandbox}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
