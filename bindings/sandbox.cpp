// Lua states for untrusted scripts (see sandbox.hpp).
//
// Functions that Lua calls raise errors only after every C++ local is gone:
// the C module runs on a C-compiled Lua, where an error is a longjmp.
#include "sandbox.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <system_error>
#include <unordered_map>

#include "ashlar_lua.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "luax.hpp"

namespace ashlar::sandbox {

namespace fs = std::filesystem;

namespace {

// The bookkeeping of one sandboxed state: the allocator's user data, so
// every thread (coroutine) of the state finds it with lua_getallocf.
struct Box {
  Settings settings;
  fs::path base;                   // absolute: where relative paths start
  std::vector<fs::path> readable;  // canonical; the write folders too
  std::vector<fs::path> writable;  // canonical
  lua_State* main = nullptr;       // the main thread, once the state exists
  // "chunk:line:" of the main thread's Lua code at the last refused
  // allocation (a fixed buffer: the allocator must not allocate).
  char refused_at[LUA_IDSIZE + 24] = "";
  Clock::time_point deadline = Clock::time_point::max();
  std::size_t used = 0;
  std::size_t peak = 0;
  std::size_t refused_allocations = 0;
  std::uint64_t instructions = 0;
  Limit exceeded = Limit::none;
  // Userdata to release if Lua frees them unfinalized, by the end of their
  // memory, which is the end of the block Lua frees (see watch_userdata).
  struct Watched {
    void* memory;
    void (*release)(void* memory);
  };
  std::unordered_map<const char*, Watched> watched;
};

// Notes where the main thread's Lua code is (the innermost Lua function's
// line: past C functions, such as string.rep, or coroutine.resume while a
// coroutine runs). Called by the allocator: lua_getstack and lua_getinfo
// with "Sl" only read the call frames, which are whole at any allocation.
void note_refused_allocation(Box& box) {
  box.refused_at[0] = '\0';
  if (box.main == nullptr) return;  // still making the state
  lua_Debug frame;
  for (int level = 0; lua_getstack(box.main, level, &frame) != 0; ++level) {
    if (lua_getinfo(box.main, "Sl", &frame) != 0 && frame.currentline > 0) {
      std::snprintf(box.refused_at, sizeof box.refused_at, "%s:%d:", frame.short_src, frame.currentline);
      return;
    }
  }
}

void* limited_allocate(void* user_data, void* block, std::size_t old_size, std::size_t new_size) {
  Box& box = *static_cast<Box*>(user_data);
  const std::size_t old_bytes = block != nullptr ? old_size : 0;  // else old_size is a type tag
  if (new_size == 0) {
    if (block != nullptr && !box.watched.empty()) {
      const auto watched = box.watched.find(static_cast<const char*>(block) + old_bytes);
      if (watched != box.watched.end()) {
        watched->second.release(watched->second.memory);
        box.watched.erase(watched);
      }
    }
    std::free(block);
    box.used -= old_bytes;
    return nullptr;
  }
  const std::size_t limit = box.settings.memory_bytes;
  if (limit != 0 && new_size > old_bytes && box.used - old_bytes + new_size > limit) {
    ++box.refused_allocations;
    if (box.exceeded == Limit::none) box.exceeded = Limit::memory;
    note_refused_allocation(box);
    return nullptr;  // Lua collects garbage and tries once more before raising
  }
  void* resized = std::realloc(block, new_size);
  if (resized == nullptr) return nullptr;
  box.used = box.used - old_bytes + new_size;
  box.peak = std::max(box.peak, box.used);
  return resized;
}

Box* box_of(lua_State* L) {
  void* user_data = nullptr;
  return lua_getallocf(L, &user_data) == limited_allocate ? static_cast<Box*>(user_data) : nullptr;
}

// A number as a person writes it: 64, 0.5, 1e+09.
std::string shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string megabytes(std::size_t bytes) {
  return shortest(static_cast<double>(bytes) / (1024.0 * 1024.0)) + " MiB";
}

std::string limit_message(Limit limit, const Settings& settings) {
  switch (limit) {
    case Limit::memory:
      return "sandbox: memory limit of " + megabytes(settings.memory_bytes) + " exceeded (the script's Lua heap)";
    case Limit::instructions:
      return "sandbox: instruction budget of " + std::to_string(settings.instructions) + " exceeded";
    case Limit::time:
      return "sandbox: time limit of " + shortest(settings.seconds) + " s exceeded";
    case Limit::none:
      break;
  }
  return {};
}

// Every kHookInterval instructions. Past a limit it fires at every
// instruction, so a script that catches the error still cannot go on.
void budget_hook(lua_State* L, lua_Debug*) {
  Box& box = *box_of(L);
  if (box.exceeded != Limit::instructions && box.exceeded != Limit::time) {
    box.instructions += kHookInterval;
    if (box.settings.instructions != 0 && box.instructions > box.settings.instructions)
      box.exceeded = Limit::instructions;
    else if (Clock::now() >= box.deadline)
      box.exceeded = Limit::time;
    else
      return;
  }
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
  const bool pushed = [&] {
    const std::string message = limit_message(box.exceeded, box.settings);
    return lua::push_message(L, message.c_str());
  }();
  if (pushed) {
    luaL_where(L, 0);  // the running function's line: a hook has no frame of its own
    lua_insert(L, -2);
    lua_concat(L, 2);
  }
  lua_error(L);
}

fs::path canonical_folder(const std::string& folder) {
  std::error_code error;
  const fs::path resolved = fs::canonical(folder.empty() ? "." : folder, error);
  if (error || !fs::is_directory(resolved))
    throw Error("sandbox: allowed folder '" + folder + "' is not an existing folder");
  return resolved;
}

// Whether `path` is `folder` or lies beneath it, comparing whole components.
bool lies_under(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // the empty element of a trailing "/"
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

std::string folder_list(const std::vector<fs::path>& folders) {
  std::vector<std::string> names;
  for (const fs::path& folder : folders) names.push_back(folder.string());
  return names.empty() ? "none" : join(names, ", ");
}

// `path` as a script of the box gives it, from the base folder.
fs::path from_base(const Box& box, const std::string& path) { return box.base / path; }

std::string problem_in_box(const Box& box, const std::string& path, Access access) {
  const char* verb = access == Access::read ? "reading" : "writing";
  if (path.empty()) return std::string("sandbox: ") + verb + " a file needs a non-empty path";
  if (path.find('\0') != std::string::npos) return "sandbox: a path may not contain a zero byte";
  std::error_code error;
  // Resolves symlinks in the part that exists and ".." everywhere.
  const fs::path resolved = fs::weakly_canonical(from_base(box, path), error);
  const auto& allowed = access == Access::read ? box.readable : box.writable;
  if (!error && std::any_of(allowed.begin(), allowed.end(),
                            [&](const fs::path& folder) { return lies_under(resolved, folder); }))
    return {};
  return std::string("sandbox: ") + verb + " '" + path + "' is not allowed" +
         (error || resolved.string() == path ? "" : " (it resolves to '" + resolved.string() + "')") +
         ": outside the allowed folders for " + verb + ": " + folder_list(allowed);
}

// What checking a path argument of a wrapped function found.
enum class PathCheck {
  allowed,  // the argument is now the file it names (script_path)
  refused,  // why not is on top of the stack
  raise,    // no memory for either: the memory error's object is on top
};

// Checks the string at stack index `index` for `access`.
PathCheck check_path_at(lua_State* L, int index, Access access) {
  index = lua_absindex(L, index);
  bool allowed = false;
  {
    std::size_t length = 0;
    const char* text = lua_tolstring(L, index, &length);
    const std::string path(text, length);  // with any zero byte, which access_problem refuses
    const std::string problem = access_problem(L, path, access);
    allowed = problem.empty();
    if (!lua::push_message(L, (allowed ? script_path(L, path) : problem).c_str())) return PathCheck::raise;
  }
  // A Lua string now, and no C++ object is alive.
  if (!allowed) return PathCheck::refused;
  lua_replace(L, index);
  return PathCheck::allowed;
}

// Raises the refusal on top of the stack with the caller's file:line.
int raise_refusal(lua_State* L) {
  luaL_where(L, 1);
  lua_insert(L, -2);
  lua_concat(L, 2);
  return lua_error(L);
}

// Returns what stock Lua returns when the system refuses a file: nil, the
// message on top of the stack, and an errno (EACCES) when `with_code`.
int return_refusal(lua_State* L, bool with_code) {
  lua_pushnil(L);
  lua_insert(L, -2);
  if (!with_code) return 2;
  lua_pushinteger(L, EACCES);
  return 3;
}

// Calls the original function (upvalue 1) with the arguments as they are.
int call_original(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

int checked_open(lua_State* L) {
  luaL_checkstring(L, 1);
  const char* mode = luaL_optstring(L, 2, "r");
  const Access access = mode[0] == 'r' && std::strchr(mode, '+') == nullptr ? Access::read : Access::write;
  switch (check_path_at(L, 1, access)) {
    case PathCheck::allowed: return call_original(L);
    case PathCheck::refused: return return_refusal(L, true);
    case PathCheck::raise: break;
  }
  return lua_error(L);
}

// io.lines and io.input read a named file; io.output writes one. Stock Lua
// raises when it cannot open the file, and so do they.
template <Access kAccess>
int checked_when_named(lua_State* L) {
  if (lua_type(L, 1) == LUA_TSTRING) {
    switch (check_path_at(L, 1, kAccess)) {
      case PathCheck::allowed: break;
      case PathCheck::refused: return raise_refusal(L);
      case PathCheck::raise: return lua_error(L);
    }
  }
  return call_original(L);
}

int checked_remove(lua_State* L) {
  luaL_checkstring(L, 1);
  switch (check_path_at(L, 1, Access::write)) {
    case PathCheck::allowed: return call_original(L);
    case PathCheck::refused: return return_refusal(L, true);
    case PathCheck::raise: break;
  }
  return lua_error(L);
}

int checked_rename(lua_State* L) {
  luaL_checkstring(L, 1);
  luaL_checkstring(L, 2);
  for (const int index : {1, 2}) {
    switch (check_path_at(L, index, Access::write)) {
      case PathCheck::allowed: break;
      case PathCheck::refused: return return_refusal(L, true);
      case PathCheck::raise: return lua_error(L);
    }
  }
  return call_original(L);
}

// load(chunk [, name [, mode [, env]]]) with the mode forced to text.
int text_load(lua_State* L) {
  if (lua_gettop(L) < 3) lua_settop(L, 3);
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  return call_original(L);
}

// loadfile returns nil and the reason, as stock Lua's does for a file it
// cannot open.
int text_loadfile(lua_State* L) {
  if (luaL_optstring(L, 1, nullptr) != nullptr) {
    switch (check_path_at(L, 1, Access::read)) {
      case PathCheck::allowed: break;
      case PathCheck::refused: return return_refusal(L, false);
      case PathCheck::raise: return lua_error(L);
    }
  }
  if (lua_gettop(L) < 2) lua_settop(L, 2);
  lua_pushliteral(L, "t");
  lua_replace(L, 2);
  return call_original(L);
}

int text_dofile(lua_State* L) {
  const bool named = luaL_optstring(L, 1, nullptr) != nullptr;
  lua_settop(L, 1);
  if (named) {
    switch (check_path_at(L, 1, Access::read)) {
      case PathCheck::allowed: break;
      case PathCheck::refused: return raise_refusal(L);
      case PathCheck::raise: return lua_error(L);
    }
  }
  if (luaL_loadfilex(L, lua_tostring(L, 1), "t") != LUA_OK) return lua_error(L);
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

// package.searchers' Lua searcher, reading only allowed files as text. Its
// strings are Lua strings on the stack, as in Lua's own searcher.
int text_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_getfield(L, lua_upvalueindex(1), "path");
  const char* templates = lua_tostring(L, -1);
  if (templates == nullptr) return luaL_error(L, "'package.path' must be a string");
  const char* file_name = luaL_gsub(L, name, ".", "/");
  lua_pushliteral(L, "");  // the files tried, for the message when none is found
  const int tried = lua_gettop(L);
  for (const char* start = templates; *start != '\0';) {
    const char* end = std::strchr(start, ';');
    if (end == nullptr) end = start + std::strlen(start);
    lua_pushlstring(L, start, static_cast<std::size_t>(end - start));
    start = *end == ';' ? end + 1 : end;
    if (lua_rawlen(L, -1) == 0) {
      lua_pop(L, 1);
      continue;
    }
    luaL_gsub(L, lua_tostring(L, -1), "?", file_name);
    lua_remove(L, -2);  // the template
    lua_pushvalue(L, -1);  // the candidate, and the file it names once checked
    const PathCheck check = check_path_at(L, -1, Access::read);
    if (check == PathCheck::raise) return lua_error(L);
    const bool allowed = check == PathCheck::allowed;
    if (allowed) {
      const char* file_path = lua_tostring(L, -1);
      if (FILE* file = std::fopen(file_path, "r")) {
        std::fclose(file);
        if (luaL_loadfilex(L, file_path, "t") != LUA_OK)
          return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, file_path,
                            lua_tostring(L, -1));
        lua_insert(L, -2);  // the chunk, then its file (the loader's second argument)
        return 2;
      }
    }
    lua_pop(L, 1);  // the file, or why not
    lua_pushvalue(L, tried);
    lua_pushliteral(L, "\n\tno file '");
    lua_pushvalue(L, -3);
    lua_pushstring(L, allowed ? "'" : "' (outside the sandbox)");
    lua_concat(L, 4);
    lua_replace(L, tried);
    lua_pop(L, 1);  // the candidate
  }
  lua_pushvalue(L, tried);
  return 1;
}

int refuse(lua_State* L) {
  return luaL_error(L, "%s is not allowed in the sandbox", lua_tostring(L, lua_upvalueindex(1)));
}

// Sets table[field] (the table on top of the stack) to a stub that raises
// "<qualified> is not allowed in the sandbox".
void refuse_field(lua_State* L, const char* field, const char* qualified) {
  lua_pushstring(L, qualified);
  lua_pushcclosure(L, refuse, 1);
  lua_setfield(L, -2, field);
}

// Wraps table[field] (the table on top of the stack): `wrapper` gets the
// original as its upvalue.
void wrap_field(lua_State* L, const char* field, lua_CFunction wrapper) {
  lua_getfield(L, -1, field);
  lua_pushcclosure(L, wrapper, 1);
  lua_setfield(L, -2, field);
}

void restrict_base(lua_State* L) {
  lua_pushglobaltable(L);
  wrap_field(L, "load", text_load);
  wrap_field(L, "loadfile", text_loadfile);
  wrap_field(L, "dofile", text_dofile);
  lua_pushnil(L);
  lua_setfield(L, -2, "debug");
  lua_pop(L, 1);
}

void restrict_io_and_os(lua_State* L) {
  lua_getglobal(L, "io");
  wrap_field(L, "open", checked_open);
  wrap_field(L, "lines", checked_when_named<Access::read>);
  wrap_field(L, "input", checked_when_named<Access::read>);
  wrap_field(L, "output", checked_when_named<Access::write>);
  refuse_field(L, "popen", "io.popen");
  refuse_field(L, "tmpfile", "io.tmpfile");
  lua_pop(L, 1);

  lua_getglobal(L, "os");
  wrap_field(L, "remove", checked_remove);
  wrap_field(L, "rename", checked_rename);
  refuse_field(L, "execute", "os.execute");
  refuse_field(L, "exit", "os.exit");
  refuse_field(L, "getenv", "os.getenv");
  refuse_field(L, "setlocale", "os.setlocale");
  refuse_field(L, "tmpname", "os.tmpname");
  lua_pop(L, 1);

  lua_getglobal(L, "string");
  refuse_field(L, "dump", "string.dump");
  lua_pop(L, 1);
}

void restrict_package(lua_State* L) {
  lua_getglobal(L, "package");
  refuse_field(L, "loadlib", "package.loadlib");
  refuse_field(L, "searchpath", "package.searchpath");
  lua_pushliteral(L, "");
  lua_setfield(L, -2, "cpath");
  lua_getfield(L, -1, "loaded");
  lua_pushnil(L);
  lua_setfield(L, -2, "debug");
  lua_pop(L, 1);
  // Only the preload searcher stays: the others load C libraries or read
  // any file, in binary too.
  lua_createtable(L, 2, 0);
  lua_getfield(L, -2, "searchers");
  lua_rawgeti(L, -1, 1);
  lua_rawseti(L, -3, 1);
  lua_pop(L, 1);
  lua_pushvalue(L, -2);
  lua_pushcclosure(L, text_searcher, 1);
  lua_rawseti(L, -2, 2);
  lua_setfield(L, -2, "searchers");
  lua_pop(L, 1);
}

// getmetatable on an ashlar object gives its type name, so that a script
// cannot replace __gc or __index of every object of the type.
void protect_ashlar_metatables(lua_State* L) {
  lua_pushnil(L);
  while (lua_next(L, LUA_REGISTRYINDEX) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_type(L, -1) == LUA_TTABLE &&
        std::strncmp(lua_tostring(L, -2), "ashlar.", 7) == 0) {
      lua_pushvalue(L, -2);
      lua_setfield(L, -2, "__metatable");
    }
    lua_pop(L, 1);
  }
}

int open_sandboxed_libraries(lua_State* L) {
  luaL_openlibs(L);
  lua_gc(L, LUA_GCGEN, 0, 0);
  luaL_requiref(L, "ashlar", ashlar_open_library, 0);
  lua_pop(L, 1);
  ashlar_add_model_path(L);
  protect_ashlar_metatables(L);
  restrict_base(L);
  restrict_io_and_os(L);
  restrict_package(L);
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, kHookInterval);
  return 0;
}

// The model library ships with ashlar; scripts may always read it.
std::string model_library_folder(lua_State* L) {
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  std::string templates = lua_tostring(L, -1) ? lua_tostring(L, -1) : "";
  lua_pop(L, 2);
  const std::size_t last = templates.rfind("/?/init.lua");
  const std::size_t start = templates.rfind(';', last);
  if (last == std::string::npos) return {};
  return templates.substr(start == std::string::npos ? 0 : start + 1, last - (start == std::string::npos ? 0 : start + 1));
}

}  // namespace

const char* limit_name(Limit limit) {
  switch (limit) {
    case Limit::none: return "none";
    case Limit::memory: return "memory";
    case Limit::instructions: return "instructions";
    case Limit::time: return "time";
  }
  return "none";
}

lua_State* new_state(const Settings& settings) {
  return new_state(settings, settings.seconds > 0
                                 ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                      std::chrono::duration<double>(settings.seconds))
                                 : Clock::time_point::max());
}

lua_State* new_state(const Settings& settings, Clock::time_point deadline) {
  if (!(settings.seconds >= 0)) throw InvalidArgument("sandbox: seconds must be >= 0");
  auto box = std::make_unique<Box>();
  box->settings = settings;
  box->deadline = deadline;
  std::error_code error;
  box->base = fs::absolute(settings.base_folder.empty() ? "." : settings.base_folder, error).lexically_normal();
  if (error) throw Error("sandbox: base folder '" + settings.base_folder + "': " + error.message());
  for (const std::string& folder : settings.write_folders) box->writable.push_back(canonical_folder(folder));
  box->readable = box->writable;
  for (const std::string& folder : settings.read_folders) box->readable.push_back(canonical_folder(folder));
  lua_State* L = lua_newstate(limited_allocate, box.get());
  if (L == nullptr) throw Error("sandbox: not enough memory for a Lua state (memory limit " + megabytes(settings.memory_bytes) + ")");
  Box* kept = box.release();  // close_state frees it after the state
  kept->main = L;
  lua_pushcfunction(L, open_sandboxed_libraries);
  if (lua_pcall(L, 0, 0, 0) != LUA_OK) {
    const std::string problem = explain_error(L, lua_tostring(L, -1) ? lua_tostring(L, -1) : "an error object");
    close_state(L);
    throw Error("sandbox: cannot open the libraries: " + problem);
  }
  std::error_code ignored;
  const std::string models = model_library_folder(L);
  if (!models.empty() && fs::is_directory(models, ignored)) kept->readable.push_back(canonical_folder(models));
  return L;
}

void restore_hook(lua_State* L) {
  if (box_of(L) != nullptr) lua_sethook(L, budget_hook, LUA_MASKCOUNT, kHookInterval);
}

void close_state(lua_State* L) {
  Box* box = box_of(L);
  // Closing calls the finalizers, which takes memory (a stack for each
  // call): at the cap a finalizer would be skipped, and what its userdata
  // holds (an engine object) would leak.
  if (box != nullptr) box->settings.memory_bytes = 0;
  lua_close(L);
  delete box;
}

void watch_userdata(lua_State* L, void* memory, std::size_t size, void (*release)(void* memory)) {
  if (Box* box = box_of(L)) box->watched[static_cast<const char*>(memory) + size] = {memory, release};
}

void forget_userdata(lua_State* L, const void* memory, std::size_t size) {
  if (Box* box = box_of(L)) box->watched.erase(static_cast<const char*>(memory) + size);
}

const Settings* settings_of(lua_State* L) {
  const Box* box = box_of(L);
  return box ? &box->settings : nullptr;
}

Clock::time_point deadline_of(lua_State* L) {
  const Box* box = box_of(L);
  return box ? box->deadline : Clock::time_point::max();
}

Usage usage_of(lua_State* L) {
  Usage usage;
  if (const Box* box = box_of(L)) {
    usage.memory_bytes = box->used;
    usage.memory_peak_bytes = box->peak;
    usage.instructions = box->instructions;
    usage.exceeded = box->exceeded;
  }
  return usage;
}

std::string deadline_problem(lua_State* L) {
  Box* box = box_of(L);
  if (box == nullptr || Clock::now() < box->deadline) return {};
  if (box->exceeded == Limit::none || box->exceeded == Limit::memory) box->exceeded = Limit::time;
  return limit_message(Limit::time, box->settings);
}

bool budget_exhausted(lua_State* L) {
  const Box* box = box_of(L);
  return box != nullptr && (box->exceeded == Limit::instructions || box->exceeded == Limit::time);
}

std::string explain_error(lua_State* L, const std::string& message) {
  const Box* box = box_of(L);
  if (box == nullptr || box->refused_allocations == 0) return message;
  const std::size_t at = message.find("not enough memory");
  if (at == std::string::npos) return message;
  // Lua's own message, as raised: it has no position, so give the one noted.
  const std::string where = at == 0 && box->refused_at[0] != '\0' ? std::string(box->refused_at) + " " : "";
  return message.substr(0, at) + where + limit_message(Limit::memory, box->settings) +
         message.substr(at + std::strlen("not enough memory"));
}

std::string script_path(lua_State* L, const std::string& path) {
  const Box* box = box_of(L);
  return box ? from_base(*box, path).string() : path;
}

std::string access_problem(lua_State* L, const std::string& path, Access access) {
  const Box* box = box_of(L);
  return box ? problem_in_box(*box, path, access) : std::string();
}

std::string require_access(lua_State* L, int arg, const std::string& what, const std::string& path, Access access) {
  const std::string problem = access_problem(L, path, access);
  if (!problem.empty()) throw lua::ArgError(arg, what + ": " + problem);
  return script_path(L, path);
}

std::string checked_path(lua_State* L, int arg, const char* what, Access access) {
  return require_access(L, arg, what, lua::check_string(L, arg, what), access);
}

}  // namespace ashlar::sandbox
