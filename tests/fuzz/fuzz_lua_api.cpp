// Fuzz target: the argument checking of the Lua API. Each input is decoded
// into a short sequence of calls, in a Lua state opened as the ashlar host
// opens it: functions of the `ashlar` table and methods of the objects they
// returned (Block, Structure, Result, FeaResult, Study, ...), with arguments
// from a pool of awkward values (nil, NaN, ±inf, huge and negative integers,
// enum names, option tables with valid and unknown keys, nested tables,
// earlier results, functions). Every call runs under pcall: success or a Lua
// error are both fine; a crash, an abort, a hang or a sanitizer report is a
// bug.
//
// The decoder never fails: past the end of the input every byte reads as 0,
// so any byte string is a valid program, and mutating one byte changes one
// choice. Sizes are bounded so that an input runs in milliseconds. Files
// the calls write (exports, saves, drawings, study databases) go to a
// temporary folder that is the working directory while an input runs: paths
// in the pool are relative and strings made from input bytes have no '/'.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <lua.hpp>

#include "host_state.hpp"
#include "scratch_folder.hpp"

namespace {

constexpr int kMaxCalls = 24;
constexpr int kMaxArguments = 4;
constexpr int kMaxDepth = 3;           // of nested tables in an argument
constexpr int kMaxListLength = 16;     // elements of a list, pairs of an option table
constexpr int kMaxStringLength = 12;   // strings made from input bytes
constexpr lua_Integer kMaxResults = 64;  // values kept for later calls; older ones are replaced

// Builders of valid objects and a few functions to pass as callbacks, so that
// a short input reaches the analyses behind the argument checks.
constexpr const char* kPrelude = R"lua(
local ashlar = require "ashlar"
local function stack()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 2, 2, 0.2 }, center = { 0, 0, -0.1 }, name = "ground" }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.1, 0, 0.25 }, name = "b1" })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.2, 0, 0.75 }, name = "b2" })
  return s
end
return {
  ashlar = ashlar,
  objects = {
    function() return ashlar.box{ size = { 1, 1, 1 } } end,
    function() return ashlar.hull{ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } end,
    stack,
    function() return require("ashlar.models").arch{ voussoirs = 6 } end,  -- loaded only when used
    function() return ashlar.analyze(stack()) end,
    function() return ashlar.fea(stack()) end,
    function() return ashlar.trace_loads(stack(), 2) end,
    function()
      return ashlar.study{ name = "canned", params = { a = { 1, 2 } },
                           run = function(p) return { v = p.a } end, progress = false }
    end,
  },
  functions = {
    function(...) return ... end,
    function() error("an error raised by a callback") end,
    function() end,
    function() return true end,
    function() return 0 / 0 end,
    function() return {} end,
    function() return { v = 1 } end,
    stack,
  },
}
)lua";

const lua_Integer kIntegers[] = {0,  1,  2,           3,           4,          8,
                                 64, -1, -2,          2147483648,  4294967297, 9007199254740993,
                                 std::numeric_limits<lua_Integer>::max(),
                                 std::numeric_limits<lua_Integer>::min()};

const double kNumbers[] = {0.0,
                           -0.0,
                           0.5,
                           1.0,
                           -1.0,
                           0.7,
                           2.5,
                           1e-12,
                           1e-300,
                           1e300,
                           -1e300,
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};

// Enum values, field names, names and patterns, and relative paths of every
// format the API reads or writes.
const char* const kStrings[] = {
    "", "a", "b1", "ground", "pyramid", "box", "lbfgs", "gradient", "all", "largest", "hinge",
    "sliding", "random", "vertical", "horizontal", "centroid", "side", "front", "lines", "points",
    "linespoints", "steps", "viridis", "von_mises", "displacement", "xx", "x", "y", "v", "stable",
    "infeasibility", "interfaces", "blocks", "status", "thrust_line", "polylines", "%", "[", "^g",
    "b%d+", "(.-)", "out.glb", "out.gltf", "out.obj", "out.ply", "out.stl", "out.json", "out.qps",
    "out.png", "out.svg", "out.pdf", "out.vtu", "out.csv", "out.db", "out", "missing.json",
    "missing/out.glb"};

// Keys of the API's option tables, and a few that no table allows.
const char* const kOptionKeys[] = {
    "absolute", "analysis", "at", "axis", "block", "cable_color", "center", "color", "confirm",
    "contact_tolerance", "contacts", "data", "db", "density", "direction", "element_size", "faces",
    "fixed", "fixed_cables", "fixed_names", "fixed_vertices", "force", "force_scale",
    "force_weight", "forces", "friction", "friction_model", "friction_sides", "from",
    "gradient_tolerance", "growth", "height", "initial_step", "interfaces", "keep_normal", "kind",
    "label", "load", "log_interval", "log_x", "log_y", "lower", "map", "mass_per_length", "max",
    "max_analyses", "max_displacement", "max_iterations", "max_relax_iterations", "max_tension",
    "method", "min", "min_volume", "name", "opacity", "orientation", "origin", "params", "path",
    "point", "poisson", "progress", "range", "reference", "refine", "relax", "release",
    "rerun_errors", "reset_peak", "result", "run", "samples", "scale", "seed", "series", "size",
    "slide_on_fixed", "stable_tolerance", "stands", "start", "stresses", "support", "symmetry",
    "tension_tolerance", "tension_weight", "threads", "thrust", "thrust_color", "title", "to",
    "together", "tolerance", "trace_color", "traces", "turn_back", "undeformed", "upper",
    "value_tolerance", "vertices", "view", "warm_start", "width", "workers", "x", "x_label", "y",
    "y_label", "young", "bogus", "Friction", ""};

// ASHLAR_FUZZ_TRACE=1 prints every call an input makes and how it ended:
// the way to turn a crashing input into a script.
const bool kTrace = std::getenv("ASHLAR_FUZZ_TRACE") != nullptr;

// A value as Lua source, near enough to paste into a script; no metamethod
// runs (they could raise).
std::string describe(lua_State* L, int idx, int depth = 0) {
  idx = lua_absindex(L, idx);
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER: {
      if (lua_isinteger(L, idx)) return std::to_string(lua_tointeger(L, idx));
      const double x = lua_tonumber(L, idx);
      if (std::isnan(x)) return "(0/0)";
      if (std::isinf(x)) return x > 0 ? "math.huge" : "-math.huge";
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", x);
      return text;
    }
    case LUA_TSTRING: {
      std::size_t length = 0;
      const char* text = lua_tolstring(L, idx, &length);
      std::string quoted = "\"";
      for (std::size_t i = 0; i < length; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '"' || c == '\\') quoted += '\\';
        if (c < 32 || c >= 127) quoted += "\\" + std::to_string(c);
        else quoted += static_cast<char>(c);
      }
      return quoted + "\"";
    }
    case LUA_TTABLE: {
      if (depth > kMaxDepth) return "{...}";
      std::string text = "{";
      lua_pushnil(L);
      while (lua_next(L, idx) != 0) {
        text += (text.size() > 1 ? ", [" : "[") + describe(L, -2, depth + 1) + "] = " + describe(L, -1, depth + 1);
        lua_pop(L, 1);
      }
      return text + "}";
    }
    case LUA_TUSERDATA:
      if (luaL_getmetafield(L, idx, "__name") == LUA_TSTRING) {
        std::string name = lua_tostring(L, -1);
        lua_pop(L, 1);
        return "<" + name + ">";
      }
      return "<userdata>";
    default:
      return luaL_typename(L, idx);
  }
}

class Input {
public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool exhausted() const { return position_ >= size_; }
  std::uint8_t byte() { return exhausted() ? 0 : data_[position_++]; }
  int below(int count) { return count <= 0 ? 0 : byte() % count; }
  template <class T, std::size_t N>
  const T& pick(const T (&items)[N]) {
    return items[byte() % N];
  }

private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

// Names of the keys of the table at idx whose values are functions, sorted
// so that a byte picks the same one in every run.
std::vector<std::string> function_names(lua_State* L, int idx) {
  std::vector<std::string> names;
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1)) names.emplace_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  std::sort(names.begin(), names.end());
  return names;
}

// One Lua state per input, so that every input replays on its own.
class Session {
public:
  explicit Session(Input& input) : in_(input), L_(luaL_newstate()) {
    if (L_ == nullptr) std::abort();
    ashlar::host::open_host_libraries(L_);
    if (luaL_loadstring(L_, kPrelude) != LUA_OK || lua_pcall(L_, 0, 1, 0) != LUA_OK) {
      std::fprintf(stderr, "fuzz prelude failed: %s\n", lua_tostring(L_, -1));
      std::abort();
    }
    prelude_ = lua_gettop(L_);
    lua_getfield(L_, prelude_, "ashlar");
    ashlar_ = lua_gettop(L_);
    ashlar_functions_ = function_names(L_, ashlar_);
    lua_newtable(L_);
    results_ = lua_gettop(L_);
  }
  ~Session() { lua_close(L_); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  void run() {
    for (int call = 0; call < kMaxCalls && !in_.exhausted(); ++call) {
      step();
      lua_settop(L_, results_);
    }
  }

private:
  void step() {
    switch (in_.below(8)) {
      case 0:
      case 1:
      case 2:
        call_ashlar_function();
        break;
      case 3:
      case 4:
        call_method();
        break;
      case 5:
        read_field();
        break;
      case 6:
        call_metamethod();
        break;
      default:
        lua_gc(L_, LUA_GCCOLLECT);  // runs __gc of objects that earlier results dropped
        break;
    }
  }

  void call_ashlar_function() {
    const std::string& name = ashlar_functions_[static_cast<std::size_t>(
        in_.below(static_cast<int>(ashlar_functions_.size())))];
    lua_getfield(L_, ashlar_, name.c_str());
    call(lua_gettop(L_), in_.below(kMaxArguments + 1), "ashlar." + name);
  }

  // obj:method(args...): a method of the object's own type when its
  // __index is a table, otherwise a name from the string pool (Result and
  // FeaResult give their fields and methods through an __index function).
  void call_method() {
    if (!push_earlier_result()) return;
    const int object = lua_gettop(L_);
    std::vector<std::string> methods;
    if (lua_type(L_, object) == LUA_TUSERDATA && lua_getmetatable(L_, object)) {
      if (lua_getfield(L_, -1, "__index") == LUA_TTABLE) methods = function_names(L_, -1);
      lua_pop(L_, 2);
    }
    const std::string method = methods.empty()
                                   ? in_.pick(kStrings)
                                   : methods[static_cast<std::size_t>(in_.below(static_cast<int>(methods.size())))];
    // Only userdata: string methods such as rep could ask for gigabytes.
    if (lua_type(L_, object) != LUA_TUSERDATA) return;
    lua_pushstring(L_, method.c_str());
    if (!index_protected(object)) return;
    if (!lua_isfunction(L_, -1)) {
      keep_results(object);
      return;
    }
    const int function = lua_gettop(L_);
    lua_pushvalue(L_, object);
    call(function, in_.below(kMaxArguments + 1), describe(L_, object) + "." + method);
  }

  void read_field() {
    if (!push_earlier_result()) return;
    const int object = lua_gettop(L_);
    if (in_.below(2) == 0) lua_pushstring(L_, in_.pick(kStrings));
    else lua_pushinteger(L_, in_.below(5));
    if (index_protected(object)) keep_results(object);
  }

  // tostring, #, or an explicit __close/__gc (Lua code can call them through
  // getmetatable; the object must then report itself closed, not crash).
  void call_metamethod() {
    if (!push_earlier_result()) return;
    const int object = lua_gettop(L_);
    static const char* const kMetamethods[] = {"__tostring", "__len", "__close", "__gc", "__index"};
    const char* metamethod = in_.pick(kMetamethods);
    if (lua_type(L_, object) != LUA_TUSERDATA || !lua_getmetatable(L_, object)) return;
    if (lua_getfield(L_, -1, metamethod) != LUA_TFUNCTION) return;
    const int function = lua_gettop(L_);
    lua_pushvalue(L_, object);
    call(function, in_.below(2), std::string("getmetatable(") + describe(L_, object) + ")." + metamethod);
  }

  // Calls the function at stack index `function` with the values already
  // above it and `count` new arguments, and keeps what it returns.
  // `name` says what the function is, for the trace.
  void call(int function, int count, const std::string& name) {
    luaL_checkstack(L_, count + 8, "fuzz arguments");
    for (int k = 0; k < count; ++k) push_value(0);
    const int argument_count = lua_gettop(L_) - function;
    if (kTrace) {
      std::string arguments;
      for (int idx = function + 1; idx <= lua_gettop(L_); ++idx) {
        arguments += (arguments.empty() ? "" : ", ") + describe(L_, idx);
      }
      std::fprintf(stderr, "%s(%s)\n", name.c_str(), arguments.c_str());
    }
    const int status = lua_pcall(L_, argument_count, LUA_MULTRET, 0);
    if (kTrace) {
      std::fprintf(stderr, "  -> %s\n", status == LUA_OK ? "ok" : describe(L_, -1).c_str());
    }
    if (status == LUA_OK) keep_results(function - 1);
  }

  // Replaces the key on top of the stack by object[key], under pcall since
  // __index may raise; false (and the error on top) when it did.
  bool index_protected(int object) {
    lua_pushcfunction(L_, [](lua_State* L) {
      lua_gettable(L, 1);
      return 1;
    });
    lua_insert(L_, -2);
    lua_pushvalue(L_, object);
    lua_insert(L_, -2);
    return lua_pcall(L_, 2, 1, 0) == LUA_OK;
  }

  // Stores the values above stack index `below` in the results table.
  void keep_results(int below) {
    for (int idx = below + 1; idx <= lua_gettop(L_); ++idx) {
      if (lua_isnil(L_, idx)) continue;
      lua_pushvalue(L_, idx);
      lua_rawseti(L_, results_, result_count_ % kMaxResults + 1);
      ++result_count_;
    }
  }

  bool push_earlier_result() {
    const lua_Integer stored = std::min(result_count_, kMaxResults);
    if (stored == 0) {
      push_canned(in_.byte());
      return !lua_isnil(L_, -1);
    }
    lua_rawgeti(L_, results_, in_.byte() % stored + 1);
    return true;
  }

  // Calls the prelude's builder `choice` (modulo their count); nil on error.
  void push_canned(std::uint8_t choice) {
    lua_getfield(L_, prelude_, "objects");
    const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L_, -1));
    lua_rawgeti(L_, -1, choice % count + 1);
    lua_remove(L_, -2);
    if (lua_pcall(L_, 0, 1, 0) != LUA_OK) {
      std::fprintf(stderr, "fuzz prelude object %d failed: %s\n", choice % static_cast<int>(count) + 1,
                   lua_tostring(L_, -1));
      std::abort();
    }
  }

  void push_value(int depth) {
    luaL_checkstack(L_, 4, "fuzz value");
    const bool nested_allowed = depth < kMaxDepth;
    switch (in_.below(18)) {
      case 0:
        lua_pushnil(L_);
        break;
      case 1:
        lua_pushboolean(L_, in_.below(2));
        break;
      case 2:
        lua_pushinteger(L_, in_.pick(kIntegers));
        break;
      case 3:
        lua_pushnumber(L_, in_.pick(kNumbers));
        break;
      case 4:
      case 5:
        lua_pushnumber(L_, small_number());
        break;
      case 6:
        lua_pushstring(L_, in_.pick(kStrings));
        break;
      case 7:
        push_input_string();
        break;
      case 8:
        push_number_list(3);
        break;
      case 9:
        push_number_list(in_.below(kMaxListLength + 1));
        break;
      case 10:
        push_point_list();
        break;
      case 11:
        push_face_list();
        break;
      case 12:
      case 13:
        if (nested_allowed) push_option_table(depth);
        else lua_pushnumber(L_, small_number());
        break;
      case 14:
        if (nested_allowed) push_value_list(depth);
        else lua_pushnil(L_);
        break;
      case 15:
        if (!push_earlier_result()) lua_pushnil(L_);
        break;
      case 16:
        push_canned(in_.byte());
        break;
      default:
        push_function();
        break;
    }
  }

  // A number of the size models use: a whole number in [-128, 128) or an
  // eighth in [-16, 16).
  double small_number() {
    const int value = static_cast<int>(in_.byte()) - 128;
    return in_.below(2) == 0 ? value / 8.0 : value;
  }

  double coordinate() { return in_.below(8) == 0 ? in_.pick(kNumbers) : small_number(); }

  void push_input_string() {
    std::string text(static_cast<std::size_t>(in_.below(kMaxStringLength + 1)), ' ');
    for (char& c : text) {
      c = static_cast<char>(in_.byte());
      if (c == '/') c = '_';  // keeps paths inside the working folder
    }
    lua_pushlstring(L_, text.data(), text.size());
  }

  void push_number_list(int count) {
    lua_createtable(L_, count, 0);
    for (int k = 1; k <= count; ++k) {
      lua_pushnumber(L_, coordinate());
      lua_rawseti(L_, -2, k);
    }
  }

  void push_point_list() {
    const int count = in_.below(kMaxListLength + 1);
    lua_createtable(L_, count, 0);
    for (int k = 1; k <= count; ++k) {
      push_number_list(in_.below(8) == 0 ? in_.below(5) : 3);
      lua_rawseti(L_, -2, k);
    }
  }

  // Faces of 1-based vertex indices, mostly in the range of a small block.
  void push_face_list() {
    const int count = in_.below(kMaxListLength + 1);
    lua_createtable(L_, count, 0);
    for (int f = 1; f <= count; ++f) {
      const int corners = in_.below(7);
      lua_createtable(L_, corners, 0);
      for (int k = 1; k <= corners; ++k) {
        lua_pushinteger(L_, in_.below(16) == 0 ? in_.pick(kIntegers) : in_.below(10));
        lua_rawseti(L_, -2, k);
      }
      lua_rawseti(L_, -2, f);
    }
  }

  void push_option_table(int depth) {
    const int count = in_.below(kMaxListLength + 1);
    lua_createtable(L_, 0, count);
    for (int k = 0; k < count; ++k) {
      lua_pushstring(L_, in_.pick(kOptionKeys));
      push_value(depth + 1);
      lua_rawset(L_, -3);
    }
  }

  void push_value_list(int depth) {
    const int count = in_.below(kMaxListLength + 1);
    lua_createtable(L_, count, 0);
    for (int k = 1; k <= count; ++k) {
      push_value(depth + 1);
      lua_rawseti(L_, -2, k);
    }
  }

  void push_function() {
    lua_getfield(L_, prelude_, "functions");
    const int count = static_cast<int>(lua_rawlen(L_, -1));
    lua_rawgeti(L_, -1, in_.below(count) + 1);
    lua_remove(L_, -2);
  }

  Input& in_;
  lua_State* L_;
  int prelude_ = 0;  // stack index of the prelude's table
  int ashlar_ = 0;   // stack index of the `ashlar` table
  int results_ = 0;  // stack index of the table of kept results
  lua_Integer result_count_ = 0;
  std::vector<std::string> ashlar_functions_;
};

// The calls of one input run in a folder of their own, so that the files
// they write (relative paths) land there. The working directory is restored
// after each input: libFuzzer and the corpus driver name their files by
// paths that may be relative.
class InScratchFolder {
public:
  InScratchFolder() : previous_(open(".", O_RDONLY | O_DIRECTORY)) {
    static const ashlar::fuzz::ScratchFolder folder("ashlar-fuzz-lua");
    if (previous_ < 0 || chdir(folder.path().c_str()) != 0) std::abort();
  }
  ~InScratchFolder() {
    if (fchdir(previous_) != 0) std::abort();
    close(previous_);
  }
  InScratchFolder(const InScratchFolder&) = delete;
  InScratchFolder& operator=(const InScratchFolder&) = delete;

private:
  int previous_;
};

}  // namespace

// fontconfig, which cairo uses for the text of drawings and charts, keeps
// its configuration until the process ends: not a leak of ours.
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const InScratchFolder in_scratch_folder;
  Input input(data, size);
  Session(input).run();
  return 0;
}
