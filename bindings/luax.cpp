#include "luax.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/text.hpp"

namespace ashlar::lua {

namespace {

// Position of the calling Lua code ("file:line: "), as luaL_error gives.
void push_where(lua_State* L) { luaL_where(L, 1); }

struct Text {
  const char* data;
  std::size_t size;
};

int push_text(lua_State* L) {
  const Text& text = *static_cast<const Text*>(lua_touserdata(L, 1));
  lua_pushlstring(L, text.data, text.size);
  return 1;
}

// Pushes `text` under lua_pcall: false, with the error's object pushed
// instead, when Lua has no memory for it.
bool push_text_protected(lua_State* L, Text text) {
  lua_pushcfunction(L, push_text);
  lua_pushlightuserdata(L, &text);
  return lua_pcall(L, 1, 1, 0) == LUA_OK;
}

}  // namespace

bool push_message(lua_State* L, const char* text) {
  // An error is raised next: the arguments may go if the stack cannot grow.
  if (!lua_checkstack(L, 2)) lua_settop(L, 0);
  return push_text_protected(L, Text{text, std::strlen(text)});
}

int get_field(lua_State* L, int idx, const char* key) {
  lua_pushvalue(L, idx);
  call_protected(L, 1, [key](lua_State* S) {
    lua_getfield(S, 1, key);
    return 1;
  });
  return lua_type(L, -1);
}

bool matches_pattern(lua_State* L, const char* text, const char* pattern) {
  call_protected(L, 0, [&](lua_State* S) {  // string.find, the text, the pattern
    lua_getglobal(S, "string");
    lua_getfield(S, -1, "find");
    lua_remove(S, -2);
    lua_pushstring(S, text);
    lua_pushstring(S, pattern);
    return 3;
  });
  protected_call(L, 2, 1);
  const bool found = !lua_isnil(L, -1);
  lua_pop(L, 1);
  return found;
}

int push_string(lua_State* L, const std::string& text) {
  if (!lua_checkstack(L, 2)) throw std::bad_alloc();
  if (!push_text_protected(L, Text{text.data(), text.size()})) throw LuaError();
  return 1;
}

int raise_pending_error(lua_State* L, int arg) {
  // The message is on top of the stack; no C++ object is alive any more.
  if (arg == kRaiseAsIs) return lua_error(L);
  if (arg > 0) return luaL_argerror(L, arg, lua_tostring(L, -1));
  push_where(L);
  lua_insert(L, -2);
  lua_concat(L, 2);
  return lua_error(L);
}

std::string type_name(lua_State* L, int idx) {
  const int field = luaL_getmetafield(L, idx, "__name");
  if (field != LUA_TNIL) {
    const std::string name = field == LUA_TSTRING ? lua_tostring(L, -1) : "";
    lua_pop(L, 1);
    // "ashlar.Block" reads as "Block" in messages.
    const size_t dot = name.rfind('.');
    if (!name.empty()) return dot == std::string::npos ? name : name.substr(dot + 1);
  }
  return luaL_typename(L, idx);
}

namespace {

std::string describe_number_problem(lua_State* L, int idx) {
  if (lua_type(L, idx) != LUA_TNUMBER) return "expected a number, got " + type_name(L, idx);
  const double value = lua_tonumber(L, idx);
  if (std::isnan(value)) return "expected a finite number, got nan";
  return value > 0 ? "expected a finite number, got inf" : "expected a finite number, got -inf";
}


bool finite_number_at(lua_State* L, int idx, double& out) {
  if (lua_type(L, idx) != LUA_TNUMBER) return false;
  out = lua_tonumber(L, idx);
  return std::isfinite(out);
}

}  // namespace

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, LUA_NUMBER_FMT, value);
  return text;
}

std::string lua_number_text(lua_State* L, int idx) {
  if (lua_isinteger(L, idx)) return std::to_string(lua_tointeger(L, idx));
  std::string text = number_text(lua_tonumber(L, idx));
  // Lua marks a float that looks like an integer: 2.0, not 2.
  if (text.find_first_not_of("-0123456789") == std::string::npos) text += ".0";
  return text;
}

double check_number(lua_State* L, int idx, int arg, const char* what) {
  double value = 0.0;
  if (!finite_number_at(L, idx, value)) {
    throw ArgError(arg, std::string(what) + ": " + describe_number_problem(L, idx));
  }
  return value;
}

double check_number(lua_State* L, int arg, const char* what) { return check_number(L, arg, arg, what); }

lua_Integer check_integer(lua_State* L, int idx, int arg, const char* what) {
  int is_integer = 0;
  const lua_Integer value = lua_tointegerx(L, idx, &is_integer);
  if (!is_integer || lua_type(L, idx) != LUA_TNUMBER) {
    throw ArgError(arg, std::string(what) + ": expected an integer, got " +
                            (lua_type(L, idx) == LUA_TNUMBER ? "a fractional number"
                                                             : type_name(L, idx)));
  }
  return value;
}

lua_Integer check_integer(lua_State* L, int arg, const char* what) { return check_integer(L, arg, arg, what); }

std::string check_string(lua_State* L, int arg, const char* what) {
  if (lua_type(L, arg) != LUA_TSTRING) {
    throw ArgError(arg, std::string(what) + ": expected a string, got " + type_name(L, arg));
  }
  size_t length = 0;
  const char* text = lua_tolstring(L, arg, &length);
  return std::string(text, length);
}

Vec3 to_vec3(lua_State* L, int idx, int arg, const std::string& what) {
  if (lua_type(L, idx) != LUA_TTABLE || lua_rawlen(L, idx) != 3) {
    throw ArgError(arg, what + ": expected a table of 3 numbers {x, y, z}, got " +
                            (lua_type(L, idx) == LUA_TTABLE
                                 ? "a table of length " + std::to_string(lua_rawlen(L, idx))
                                 : type_name(L, idx)));
  }
  idx = lua_absindex(L, idx);
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    lua_rawgeti(L, idx, k + 1);
    double value = 0.0;
    const bool ok = finite_number_at(L, -1, value);
    const std::string problem = ok ? std::string() : describe_number_problem(L, -1);
    lua_pop(L, 1);
    if (!ok) throw ArgError(arg, what + "[" + std::to_string(k + 1) + "]: " + problem);
    v[k] = value;
  }
  return v;
}

std::vector<Vec3> to_points(lua_State* L, int idx, int arg, const std::string& what) {
  if (lua_type(L, idx) != LUA_TTABLE) {
    throw ArgError(arg, what + ": expected a list of points {{x, y, z}, ...}, got " +
                            type_name(L, idx));
  }
  idx = lua_absindex(L, idx);
  const lua_Unsigned count = lua_rawlen(L, idx);
  std::vector<Vec3> points;
  points.reserve(count);
  for (lua_Unsigned i = 1; i <= count; ++i) {
    lua_rawgeti(L, idx, static_cast<lua_Integer>(i));
    try {
      points.push_back(to_vec3(L, -1, arg, what + "[" + std::to_string(i) + "]"));
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
    lua_pop(L, 1);
  }
  return points;
}

std::vector<FaceLoop> to_faces(lua_State* L, int idx, int arg, const std::string& what) {
  if (lua_type(L, idx) != LUA_TTABLE) {
    throw ArgError(arg, what + ": expected a list of faces {{i, j, k, ...}, ...}, got " +
                            type_name(L, idx));
  }
  idx = lua_absindex(L, idx);
  std::vector<FaceLoop> faces;
  const lua_Unsigned count = lua_rawlen(L, idx);
  for (lua_Unsigned f = 1; f <= count; ++f) {
    const std::string face_name = what + "[" + std::to_string(f) + "]";
    lua_rawgeti(L, idx, static_cast<lua_Integer>(f));
    if (lua_type(L, -1) != LUA_TTABLE) {
      const std::string got = type_name(L, -1);
      lua_pop(L, 1);
      throw ArgError(arg, face_name + ": expected a list of vertex indices, got " + got);
    }
    FaceLoop face;
    const lua_Unsigned size = lua_rawlen(L, -1);
    for (lua_Unsigned k = 1; k <= size; ++k) {
      lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
      int is_integer = 0;
      const lua_Integer index = lua_tointegerx(L, -1, &is_integer);
      lua_pop(L, 1);
      if (!is_integer || index < 1 || index > std::numeric_limits<int>::max()) {
        lua_pop(L, 1);
        throw ArgError(arg, face_name + "[" + std::to_string(k) +
                                "]: expected a vertex index (an integer >= 1)");
      }
      face.push_back(static_cast<int>(index - 1));
    }
    lua_pop(L, 1);
    faces.push_back(std::move(face));
  }
  return faces;
}

void push_vec3(lua_State* L, const Vec3& v) {
  lua_createtable(L, 3, 0);
  for (int k = 0; k < 3; ++k) {
    lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

void push_points(lua_State* L, const std::vector<Vec3>& points) {
  lua_createtable(L, static_cast<int>(points.size()), 0);
  for (size_t i = 0; i < points.size(); ++i) {
    push_vec3(L, points[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void set_field(lua_State* L, const char* key, double value) {
  lua_pushnumber(L, value);
  lua_setfield(L, -2, key);
}

void set_field(lua_State* L, const char* key, int value) { set_field(L, key, static_cast<lua_Integer>(value)); }

void set_field(lua_State* L, const char* key, lua_Integer value) {
  lua_pushinteger(L, value);
  lua_setfield(L, -2, key);
}

void set_field(lua_State* L, const char* key, const Vec3& value) {
  push_vec3(L, value);
  lua_setfield(L, -2, key);
}

void set_boolean(lua_State* L, const char* key, bool value) {
  lua_pushboolean(L, value);
  lua_setfield(L, -2, key);
}

void set_string(lua_State* L, const char* key, const char* value) {
  lua_pushstring(L, value);
  lua_setfield(L, -2, key);
}

void set_index_field(lua_State* L, const char* key, int zero_based) {
  lua_pushinteger(L, static_cast<lua_Integer>(zero_based) + 1);
  lua_setfield(L, -2, key);
}

OptionTable::OptionTable(lua_State* L, int arg, std::initializer_list<const char*> allowed)
    : L_(L), arg_(arg), index_(0) {
  const int type = lua_type(L, arg);
  if (type == LUA_TNONE || type == LUA_TNIL) return;
  if (type != LUA_TTABLE) {
    throw ArgError(arg, "expected an option table, got " + type_name(L, arg));
  }
  index_ = lua_absindex(L, arg);
  check_keys(allowed);
}

OptionTable::OptionTable(lua_State* L, int idx, int arg, std::string prefix,
                         std::initializer_list<const char*> allowed)
    : L_(L), arg_(arg), index_(lua_absindex(L, idx)), prefix_(std::move(prefix)) {
  check_keys(allowed);
}

void OptionTable::check_keys(std::initializer_list<const char*> allowed) const {
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);  // value; the key stays for lua_next
    const bool string_key = lua_type(L_, -1) == LUA_TSTRING;
    // lua_tostring would turn a number key into a string in place and break lua_next.
    const std::string key = string_key ? lua_tostring(L_, -1) : type_name(L_, -1);
    const bool known = string_key && std::any_of(allowed.begin(), allowed.end(),
                                                 [&](const char* name) { return key == name; });
    if (!known) {
      std::vector<std::string> names(allowed.begin(), allowed.end());
      std::sort(names.begin(), names.end());
      const std::string shown = string_key ? "'" + prefix_ + key + "'" : "(a " + key + " key)";
      throw ArgError(arg_, "unknown option " + shown + " (allowed: " + join(names) + ")");
    }
  }
}

void OptionTable::fail(const char* key, const std::string& message) const {
  throw ArgError(arg_, prefix_ + key + ": " + message);
}

int OptionTable::push(const char* key) const {
  if (index_ == 0) {
    lua_pushnil(L_);
    return LUA_TNIL;
  }
  return get_field(L_, index_, key);
}

bool OptionTable::has(const char* key) const {
  const bool present = push(key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

std::optional<double> OptionTable::number(const char* key) const {
  push(key);
  if (lua_isnil(L_, -1)) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  double value = 0.0;
  const bool ok = finite_number_at(L_, -1, value);
  const std::string problem = ok ? std::string() : describe_number_problem(L_, -1);
  lua_pop(L_, 1);
  if (!ok) fail(key, problem);
  return value;
}

double OptionTable::number(const char* key, double fallback) const {
  return number(key).value_or(fallback);
}

double OptionTable::positive(const char* key, double fallback, bool zero_allowed) const {
  const double value = number(key, fallback);
  if (value < 0.0 || (!zero_allowed && value == 0.0)) {
    fail(key, std::string("expected a number ") + (zero_allowed ? ">= 0" : "> 0") + ", got " +
                  number_text(value));
  }
  return value;
}

std::optional<Vec3> OptionTable::vec3(const char* key) const {
  push(key);
  if (lua_isnil(L_, -1)) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  try {
    const Vec3 v = to_vec3(L_, -1, arg_, prefix_ + key);
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

std::optional<std::string> OptionTable::string(const char* key) const {
  push(key);
  if (lua_isnil(L_, -1)) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  if (lua_type(L_, -1) != LUA_TSTRING) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "expected a string, got " + got);
  }
  std::string value = lua_tostring(L_, -1);
  lua_pop(L_, 1);
  return value;
}

std::optional<lua_Integer> OptionTable::whole(const char* key, lua_Integer least, lua_Integer most,
                                              const std::string& expected) const {
  push(key);
  if (lua_isnil(L_, -1)) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  int is_integer = 0;
  const lua_Integer value = lua_tointegerx(L_, -1, &is_integer);
  const bool number = lua_type(L_, -1) == LUA_TNUMBER;
  const std::string got = number ? lua_number_text(L_, -1) : type_name(L_, -1);
  lua_pop(L_, 1);
  if (!number || !is_integer || value < least || value > most) {
    fail(key, "expected " + expected + ", got " + got);
  }
  return value;
}

std::optional<bool> OptionTable::boolean(const char* key) const {
  push(key);
  if (lua_isnil(L_, -1)) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  if (!lua_isboolean(L_, -1)) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, "expected a boolean, got " + got);
  }
  const bool value = lua_toboolean(L_, -1);
  lua_pop(L_, 1);
  return value;
}

int image_size(const OptionTable& options, const char* key, int fallback) {
  const std::optional<lua_Integer> value =
      options.whole(key, 1, LUA_MAXINTEGER, "a positive whole number of pixels");
  // Large values reach the engine's range check, not an int overflow.
  return value ? static_cast<int>(std::min<lua_Integer>(*value, 1 << 30)) : fallback;
}

void protected_call(lua_State* L, int nargs, int nresults) {
  if (lua_pcall(L, nargs, nresults, 0) != LUA_OK) {
    std::string message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1)
                                                         : "(error object is a " +
                                                               type_name(L, -1) + " value)";
    lua_pop(L, 1);
    throw std::runtime_error(message);
  }
}

void register_type(lua_State* L, const char* metatable, const luaL_Reg* methods,
                   const luaL_Reg* metamethods) {
  luaL_newmetatable(L, metatable);
  luaL_setfuncs(L, metamethods, 0);
  if (methods) {
    lua_newtable(L);
    luaL_setfuncs(L, methods, 0);
    lua_setfield(L, -2, "__index");
  }
  lua_pop(L, 1);
}

}  // namespace ashlar::lua
