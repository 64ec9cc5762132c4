// Helpers shared by the wrap_*.cpp bindings: argument checking, option
// tables, userdata boxes and the exception boundary.
//
// Argument readers here throw ArgError instead of calling luaL_argerror, so
// that no Lua error unwinds (or, with a C-compiled Lua, longjmps) across C++
// frames that own resources. guard() is the single place where C++
// exceptions become Lua errors, after every C++ local is gone.
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <lua.hpp>

#include "core/clock.hpp"
#include "core/enum_names.hpp"
#include "core/interrupt.hpp"
#include "core/types.hpp"

namespace ashlar::sandbox {
// When a sandboxed script's time is up (sandbox.hpp); the far future outside
// a sandbox. Declared here so that guard() needs no more of the sandbox.
Clock::time_point deadline_of(lua_State* L);
}  // namespace ashlar::sandbox

namespace ashlar::lua {

// A bad argument: becomes "bad argument #arg to 'f' (message)".
class ArgError : public std::runtime_error {
public:
  ArgError(int arg, const std::string& message) : std::runtime_error(message), arg_(arg) {}
  int arg() const { return arg_; }

private:
  int arg_;
};

// Runs a binding body and converts any C++ exception into a Lua error that
// carries the calling script's file:line. Lua's own errors (the C++ build of
// Lua throws a non-std type) pass through untouched.
int raise_pending_error(lua_State* L, int arg);
template <class Body>
int guard(lua_State* L, Body&& body) {
  int arg = -1;
  try {
    // The engine's long loops stop at a sandboxed script's deadline.
    const DeadlineScope deadline(sandbox::deadline_of(L));
    return body();
  } catch (const ArgError& e) {
    arg = e.arg();
    lua_pushstring(L, e.what());
  } catch (const std::bad_alloc&) {
    arg = 0;
    lua_pushliteral(L, "not enough memory (the engine's allocation failed)");
  } catch (const std::exception& e) {
    arg = 0;
    lua_pushstring(L, e.what());
  }
  return raise_pending_error(L, arg);
}

// Name of the Lua type of the value at idx, e.g. "nil", "table", "Block".
std::string type_name(lua_State* L, int idx);

// Scalars (finite numbers only: NaN and inf are rejected).
double check_number(lua_State* L, int arg, const char* what);
lua_Integer check_integer(lua_State* L, int arg, const char* what);
std::string check_string(lua_State* L, int arg, const char* what);

// A table {x, y, z} of three finite numbers at stack index idx; `arg` and
// `what` name it in errors.
Vec3 to_vec3(lua_State* L, int idx, int arg, const std::string& what);
// A list of such points.
std::vector<Vec3> to_points(lua_State* L, int idx, int arg, const std::string& what);
// A list of faces, each a list of 1-based vertex indices; returned 0-based.
std::vector<FaceLoop> to_faces(lua_State* L, int idx, int arg, const std::string& what);

void push_vec3(lua_State* L, const Vec3& v);
void push_points(lua_State* L, const std::vector<Vec3>& points);

// Fields of the table on top of the stack.
void set_field(lua_State* L, const char* key, double value);
// Counts and indices as Lua integers (15086, not 15086.0).
void set_field(lua_State* L, const char* key, int value);
void set_field(lua_State* L, const char* key, lua_Integer value);
void set_field(lua_State* L, const char* key, const Vec3& value);
void set_boolean(lua_State* L, const char* key, bool value);
void set_string(lua_State* L, const char* key, const char* value);
// A 0-based engine index stored as the 1-based Lua index.
void set_index_field(lua_State* L, const char* key, int zero_based);

// An option table argument. Construction checks that the argument is a table
// (or absent/nil) and that every key is one of `allowed`, naming the unknown
// key and the allowed ones otherwise. Readers name the key in their errors.
// As Lua prints numbers: 0 and 2.5, not 0.000000 and 2.500000.
std::string number_text(double value);

class OptionTable {
public:
  OptionTable(lua_State* L, int arg, std::initializer_list<const char*> allowed);
  // A table nested in argument `arg` at stack index idx; errors name `prefix`
  // (e.g. "color.") before its keys.
  OptionTable(lua_State* L, int idx, int arg, std::string prefix,
              std::initializer_list<const char*> allowed);

  bool has(const char* key) const;
  std::optional<double> number(const char* key) const;
  double number(const char* key, double fallback) const;
  // A finite number > 0 (or >= 0 when zero_allowed).
  double positive(const char* key, double fallback, bool zero_allowed = false) const;
  std::optional<Vec3> vec3(const char* key) const;
  // An enum option: its name in `names`, or an error "key: 'x' is not one
  // of a, b".
  template <class Enum, std::size_t Count>
  std::optional<Enum> choice(const char* key, const EnumNames<Enum, Count>& names) const {
    const std::optional<std::string> text = string(key);
    if (!text) return std::nullopt;
    const std::optional<Enum> value = names.parse(*text);
    if (!value) fail(key, "'" + *text + "' is not one of " + names.list());
    return value;
  }
  std::optional<std::string> string(const char* key) const;
  // A whole number in [least, most]; otherwise an error "key: expected
  // <expected>, got <value>".
  std::optional<lua_Integer> whole(const char* key, lua_Integer least, lua_Integer most,
                                   const std::string& expected) const;
  std::optional<bool> boolean(const char* key) const;
  // Pushes the value of key (nil if absent) and returns its Lua type.
  int push(const char* key) const;
  int arg() const { return arg_; }
  lua_State* state() const { return L_; }

private:
  [[noreturn]] void fail(const char* key, const std::string& message) const;

  void check_keys(std::initializer_list<const char*> allowed) const;

  lua_State* L_;
  int arg_;
  int index_;  // absolute stack index, 0 when the argument was absent
  std::string prefix_;
};

// An image size option: a positive whole number of px (pt for vector
// formats), `fallback` when absent; the engine checks its range.
int image_size(const OptionTable& options, const char* key, int fallback);

// Calls the function at stack index idx with `nargs` values already pushed
// above it; on a Lua error throws std::runtime_error with its message.
// Leaves `nresults` results on the stack.
void protected_call(lua_State* L, int nargs, int nresults);

// Full userdata holding a shared pointer; reset by __gc/__close so that both
// are idempotent and a closed object is reported instead of used.
template <class T>
struct Box {
  std::shared_ptr<T> ptr;
};

template <class T>
void push_boxed(lua_State* L, std::shared_ptr<T> value, const char* metatable) {
  void* memory = lua_newuserdatauv(L, sizeof(Box<T>), 0);
  new (memory) Box<T>{std::move(value)};
  luaL_setmetatable(L, metatable);
}

template <class T>
Box<T>* test_boxed(lua_State* L, int idx, const char* metatable) {
  return static_cast<Box<T>*>(luaL_testudata(L, idx, metatable));
}

// A copy of the shared pointer held by the userdata at idx; throws ArgError
// naming the expected type, or saying the object was closed. A binding keeps
// the copy for as long as it uses the object: Lua code that runs meanwhile (a
// callback, an option table's __index, a finalizer during an allocation) may
// close the userdata.
template <class T>
std::shared_ptr<T> check_boxed(lua_State* L, int idx, const char* metatable, const char* type) {
  Box<T>* box = test_boxed<T>(L, idx, metatable);
  if (!box) throw ArgError(idx, std::string(type) + " expected, got " + type_name(L, idx));
  if (!box->ptr) throw ArgError(idx, std::string("attempt to use a closed ") + type);
  return box->ptr;
}

// For __tostring: pushes "Block (closed)" and returns true when the userdata
// at index 1 was closed, so that printing an object never raises.
template <class T>
bool push_if_closed(lua_State* L, const char* metatable, const char* type) {
  Box<T>* box = test_boxed<T>(L, 1, metatable);
  if (!box || box->ptr) return false;
  lua_pushfstring(L, "%s (closed)", type);
  return true;
}

template <class T>
int release_boxed(lua_State* L, const char* metatable) {
  if (Box<T>* box = test_boxed<T>(L, 1, metatable)) box->ptr.reset();
  return 0;
}

// For a userdata at stack index 1 with one user value: pushes the table
// cached under `key` in that user value, building it with build(L, record)
// on first access, so that large result tables are made once and only when
// read.
template <class Record>
int push_cached_table(lua_State* L, const char* key, const Record& record,
                      void (*build)(lua_State*, const Record&)) {
  if (lua_getiuservalue(L, 1, 1) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setiuservalue(L, 1, 1);
  }
  if (lua_getfield(L, -1, key) == LUA_TNIL) {
    lua_pop(L, 1);
    build(L, record);
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, key);
  }
  return 1;
}

// Registers a metatable with methods (as the __index table; nullptr when the
// metamethods give their own __index) and metamethods.
void register_type(lua_State* L, const char* metatable, const luaL_Reg* methods,
                   const luaL_Reg* metamethods);

}  // namespace ashlar::lua
