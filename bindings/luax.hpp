// Helpers shared by the wrap_*.cpp bindings: argument checking, option
// tables, userdata boxes and the exception boundary.
//
// No Lua error may unwind (or, with the C-compiled Lua of the C module,
// longjmp) across C++ frames that own resources: a longjmp skips their
// destructors. So argument readers here throw ArgError instead of calling
// luaL_argerror; Lua calls that can raise (that allocate, or run a
// metamethod) while C++ objects are alive go through call_protected, which
// turns the error into a LuaError exception; and guard() is the single
// place where exceptions become Lua errors, after every C++ local is gone.
#pragma once

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
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
// The userdata whose finalizer releases what it holds, which a sandboxed
// state's allocator releases when Lua frees them unfinalized (sandbox.hpp).
void watch_userdata(lua_State* L, void* memory, std::size_t size, void (*release)(void* memory));
void forget_userdata(lua_State* L, const void* memory, std::size_t size);
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

// A Lua error that call_protected caught: its error object is on top of
// the stack, and guard raises it as it is.
class LuaError : public std::exception {
public:
  const char* what() const noexcept override { return "Lua error (its object is on the stack)"; }
};

// Pushes `text`; when Lua has no memory for it, pushes the memory error's
// object instead and returns false.
bool push_message(lua_State* L, const char* text);

// Calls fn(L) under lua_pcall with the `nargs` values on top of the stack as
// its arguments (stack indices 1..nargs inside fn, whose frame is its own)
// and returns how many values it returned, now on top of the stack. When
// Lua raises meanwhile (no memory, a metamethod that fails), throws
// LuaError with the error object on the stack. fn holds no C++ object with
// a destructor while it calls Lua; what it reads lives outside, in the
// caller's frame, which unwinds as C++ does. An exception fn throws (a
// nested call_protected's LuaError included) becomes the Lua error.
template <class Fn>
int call_protected(lua_State* L, int nargs, Fn&& fn) {
  using F = std::remove_reference_t<Fn>;
  if (!lua_checkstack(L, 2)) throw std::bad_alloc();
  const int base = lua_gettop(L) - nargs;
  lua_pushcfunction(L, [](lua_State* S) -> int {
    F& f = *static_cast<F*>(lua_touserdata(S, -1));
    lua_pop(S, 1);
    int results = -1;
    try {
      results = f(S);
    } catch (const LuaError&) {
      // The error object is on top already.
    } catch (const std::exception& e) {
      push_message(S, e.what());  // or, without memory for it, that error's object
    }
    // Raised here, out of the handlers: a longjmp from inside one would
    // leave the exception object behind.
    return results >= 0 ? results : lua_error(S);
  });
  lua_insert(L, base + 1);
  lua_pushlightuserdata(L, const_cast<void*>(static_cast<const void*>(&fn)));
  if (lua_pcall(L, nargs + 1, LUA_MULTRET, 0) != LUA_OK) throw LuaError();
  return lua_gettop(L) - base;
}

// lua_getfield under call_protected (a table's __index may raise, and a key
// may need memory): pushes t[key] for the table at idx, returns its type.
int get_field(lua_State* L, int idx, const char* key);

// Whether string.find(text, pattern) finds the Lua pattern in text; a
// malformed pattern throws with Lua's message.
bool matches_pattern(lua_State* L, const char* text, const char* pattern);

// Pushes `text` and returns 1, under call_protected: for a string the
// caller's C++ objects hold.
int push_string(lua_State* L, const std::string& text);

// Runs a binding body and converts any C++ exception into a Lua error that
// carries the calling script's file:line. Lua's own errors (the C++ build of
// Lua throws a non-std type) pass through untouched.
constexpr int kRaiseAsIs = -1;  // raise_pending_error's arg for an error object to raise unchanged
int raise_pending_error(lua_State* L, int arg);
template <class Body>
int guard(lua_State* L, Body&& body) {
  int arg = kRaiseAsIs;
  try {
    // The engine's long loops stop at a sandboxed script's deadline.
    const DeadlineScope deadline(sandbox::deadline_of(L));
    return body();
  } catch (const LuaError&) {
    arg = kRaiseAsIs;
  } catch (const ArgError& e) {
    arg = push_message(L, e.what()) ? e.arg() : kRaiseAsIs;
  } catch (const std::bad_alloc&) {
    arg = push_message(L, "not enough memory (the engine's allocation failed)") ? 0 : kRaiseAsIs;
  } catch (const std::exception& e) {
    arg = push_message(L, e.what()) ? 0 : kRaiseAsIs;
  }
  return raise_pending_error(L, arg);
}

// Name of the Lua type of the value at idx, e.g. "nil", "table", "Block".
std::string type_name(lua_State* L, int idx);

// Scalars (finite numbers only: NaN and inf are rejected).
double check_number(lua_State* L, int arg, const char* what);
// The number at stack index idx (a value inside argument `arg`).
double check_number(lua_State* L, int idx, int arg, const char* what);
lua_Integer check_integer(lua_State* L, int arg, const char* what);
// The integer at stack index idx (a value inside argument `arg`).
lua_Integer check_integer(lua_State* L, int idx, int arg, const char* what);
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
// The number at idx as tostring gives it (2, 2.0, 2.5), without the
// allocation of lua_tostring, which converts the value in place.
std::string lua_number_text(lua_State* L, int idx);

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

// With `user_values` user values (push_cached_table keeps its tables in
// the first).
template <class T>
void push_boxed(lua_State* L, std::shared_ptr<T> value, const char* metatable, int user_values = 0) {
  // Allocated before the box holds `value`, which then belongs to the
  // userdata: setting a registered metatable allocates nothing.
  call_protected(L, 0, [user_values](lua_State* S) {
    lua_newuserdatauv(S, sizeof(Box<T>), user_values);
    return 1;
  });
  new (lua_touserdata(L, -1)) Box<T>{std::move(value)};
  luaL_setmetatable(L, metatable);
  sandbox::watch_userdata(L, lua_touserdata(L, -1), sizeof(Box<T>),
                          [](void* memory) { static_cast<Box<T>*>(memory)->ptr.reset(); });
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
  if (Box<T>* box = test_boxed<T>(L, 1, metatable)) {
    box->ptr.reset();
    sandbox::forget_userdata(L, box, sizeof(Box<T>));
  }
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
