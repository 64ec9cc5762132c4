#include "wrap_fea.hpp"

#include <cmath>
#include <cstring>

#include "fea/fea.hpp"
#include "io/fea_export.hpp"
#include "io/mesh_io.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_Structure.hpp"

namespace ashlar::lua {

namespace {

constexpr const char* kFeaMeta = "ashlar.FeaResult";

// What a Lua FeaResult holds: the structure as analysed (a copy: the
// script may change its own afterwards), the contact options it was analysed
// with, its mesh and the result.
struct FeaRecord {
  Structure structure;
  ContactOptions contact;
  std::unique_ptr<FeaMesh> mesh;
  FeaResult result;
};

std::shared_ptr<FeaRecord> check_fea_record(lua_State* L, int idx) {
  return check_boxed<FeaRecord>(L, idx, kFeaMeta, "FeaResult");
}

FeaSettings fea_settings(const OptionTable& options) {
  FeaSettings settings;
  settings.material.young = options.positive("young", settings.material.young);
  settings.material.poisson = options.number("poisson", settings.material.poisson);
  if (!(settings.material.poisson > -1 && settings.material.poisson < 0.5))
    throw ArgError(options.arg(), "poisson: expected a number in (-1, 0.5), got " +
                                      std::to_string(settings.material.poisson));
  settings.method = options.choice("method", kFeaContactModelNames).value_or(settings.method);
  settings.relax = options.boolean("relax").value_or(settings.relax);
  settings.max_relax_iterations = static_cast<int>(
      options.whole("max_relax_iterations", 0, 100000, "a whole number from 0 to 100000")
          .value_or(settings.max_relax_iterations));
  settings.release = options.choice("release", kFeaReleaseNames).value_or(settings.release);
  settings.tension_tolerance = options.positive("tension_tolerance", settings.tension_tolerance, true);
  settings.max_displacement = options.positive("max_displacement", settings.max_displacement);
  settings.stresses = options.boolean("stresses").value_or(settings.stresses);
  settings.contact.tolerance = options.positive("contact_tolerance", 0.0, true);
  return settings;
}

int w_fea(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const OptionTable options(L, 2, {"young", "poisson", "refine", "element_size", "method", "relax",
                                     "max_relax_iterations", "release", "tension_tolerance",
                                     "max_displacement", "stresses", "contact_tolerance"});
    const FeaSettings settings = fea_settings(options);
    const int refine = static_cast<int>(options.whole("refine", 1, 64, "a whole number from 1 to 64").value_or(kDefaultRefine));
    const double element_size = options.positive("element_size", 0.0, true);
    auto record = std::make_shared<FeaRecord>();
    record->structure = s;
    record->mesh = std::make_unique<FeaMesh>(record->structure, refine, element_size);
    record->result = analyze_fea(record->structure, *record->mesh, settings);
    record->contact = settings.contact;
    push_boxed(L, std::move(record), kFeaMeta, 1);
    return 1;
  });
}

void push_index_list(lua_State* L, const std::vector<int>& zero_based) {
  lua_createtable(L, static_cast<int>(zero_based.size()), 0);
  for (size_t i = 0; i < zero_based.size(); ++i) {
    lua_pushinteger(L, zero_based[i] + 1);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_displacements(lua_State* L, const FeaRecord& r) { push_points(L, r.result.displacements); }
void push_nodes(lua_State* L, const FeaRecord& r) { push_points(L, r.mesh->nodes()); }

void push_elements(lua_State* L, const FeaRecord& r) {
  const auto& elements = r.mesh->elements();
  lua_createtable(L, static_cast<int>(elements.size()), 0);
  for (size_t e = 0; e < elements.size(); ++e) {
    push_index_list(L, std::vector<int>(elements[e].begin(), elements[e].end()));
    lua_rawseti(L, -2, static_cast<lua_Integer>(e + 1));
  }
}

void push_element_blocks(lua_State* L, const FeaRecord& r) {
  std::vector<int> blocks(r.mesh->elements().size());
  for (size_t e = 0; e < blocks.size(); ++e) blocks[e] = r.mesh->element_block(static_cast<int>(e));
  push_index_list(L, blocks);
}

void push_node_blocks(lua_State* L, const FeaRecord& r) {
  std::vector<int> blocks(r.mesh->nodes().size());
  for (size_t n = 0; n < blocks.size(); ++n) blocks[n] = r.mesh->node_block(static_cast<int>(n));
  push_index_list(L, blocks);
}

void push_contacts(lua_State* L, const FeaRecord& r) {
  const std::vector<FeaContact>& contacts = r.result.contacts;
  lua_createtable(L, static_cast<int>(contacts.size()), 0);
  for (size_t t = 0; t < contacts.size(); ++t) {
    const FeaContact& c = contacts[t];
    lua_createtable(L, 0, 9);
    set_index_field(L, "interface", c.interface);
    set_index_field(L, "node", c.node);
    set_index_field(L, "block", c.block);
    set_field(L, "position", r.mesh->nodes()[c.node]);
    set_field(L, "force", c.force_on_b);
    set_field(L, "normal_force", c.normal_force);
    set_field(L, "opening", c.opening);
    set_boolean(L, "tensile", c.tensile);
    set_boolean(L, "released", c.released);
    if (c.released) set_field(L, "released_at", c.released_at);
    set_boolean(L, "ground", c.target.nodes.empty());
    lua_rawseti(L, -2, static_cast<lua_Integer>(t + 1));
  }
}

void push_released(lua_State* L, const FeaRecord& r) {
  std::vector<int> released;
  for (size_t t = 0; t < r.result.contacts.size(); ++t)
    if (r.result.contacts[t].released) released.push_back(static_cast<int>(t));
  push_index_list(L, released);
}

void push_interfaces(lua_State* L, const FeaRecord& r) {
  // Cached in the structure since the analysis found them.
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = r.structure.interfaces(r.contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  lua_createtable(L, static_cast<int>(interfaces.size()), 0);
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const FeaInterfaceForce& f = r.result.interfaces[k];
    lua_createtable(L, 0, 10);
    set_index_field(L, "a", interfaces[k].a);
    set_index_field(L, "b", interfaces[k].b);
    set_field(L, "normal_force", f.compression - f.tension);
    set_field(L, "compression", f.compression);
    set_field(L, "tension", f.tension);
    set_field(L, "resultant", f.resultant);
    set_field(L, "center_of_pressure", f.center_of_pressure);
    set_field(L, "normal", interfaces[k].normal);
    set_field(L, "contacts", f.contacts);
    set_field(L, "released", f.released);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

void push_history(lua_State* L, const FeaRecord& r) {
  const std::vector<FeaIteration>& history = r.result.history;
  lua_createtable(L, static_cast<int>(history.size()), 0);
  for (size_t i = 0; i < history.size(); ++i) {
    const FeaIteration& it = history[i];
    lua_createtable(L, 0, 8);
    set_field(L, "active", it.active);
    set_field(L, "released", i == 0 ? 0 : history[i - 1].released);
    set_field(L, "engaged", i == 0 ? 0 : history[i - 1].engaged);
    set_field(L, "tensile", it.tensile);
    set_field(L, "tension", it.tension);
    set_field(L, "max_tension", it.max_tension);
    set_field(L, "multiplier_steps", it.multiplier_steps);
    set_field(L, "constraint_error", it.constraint_error);
    set_field(L, "seconds", it.seconds);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_stresses(lua_State* L, const FeaRecord& r) {
  const std::vector<Stress>& stresses = r.result.stresses;
  lua_createtable(L, static_cast<int>(stresses.size()), 0);
  static const char* const kComponents[] = {"xx", "yy", "zz", "yz", "xz", "xy"};
  for (size_t e = 0; e < stresses.size(); ++e) {
    lua_createtable(L, 0, 7);
    for (int c = 0; c < 6; ++c) set_field(L, kComponents[c], stresses[e](c));
    set_field(L, "von_mises", von_mises(stresses[e]));
    lua_rawseti(L, -2, static_cast<lua_Integer>(e + 1));
  }
}

int w_FeaResult_export(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<FeaRecord> record = check_fea_record(L, 1);
    const FeaRecord& r = *record;
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    const OptionTable options(L, 3, {"scale", "color", "map", "undeformed", "contacts", "format"});
    if (file_extension(path) == "vtu") {
      for (const char* key : {"scale", "color", "map", "undeformed", "contacts"})
        if (options.has(key))
          throw ArgError(3, std::string(key) + ": applies to 3D files, not to .vtu, which holds every result");
      FeaVtuOptions vtu;
      vtu.format = options.choice("format", kVtuFormatNames).value_or(vtu.format);
      export_fea_vtu(r.structure, *r.mesh, r.result, *r.structure.interfaces(r.contact), path, vtu);
      return 0;
    }
    if (options.has("format"))
      throw ArgError(3, "format: applies to .vtu files, not to 3D files, whose extension gives the format");
    FeaMeshExportOptions settings;
    settings.scale = options.positive("scale", settings.scale, true);
    if (std::optional<std::string> color = options.string("color")) settings.color = *color;
    if (std::optional<std::string> map = options.string("map")) settings.map = *map;
    settings.undeformed = options.boolean("undeformed").value_or(settings.undeformed);
    settings.contacts = options.boolean("contacts").value_or(settings.contacts);
    export_fea_mesh(r.structure, *r.mesh, r.result, path, settings);
    return 0;
  });
}

// A quantity, or nil where the result gives it no meaning (NaN), so that a
// study stores NULL rather than a number.
int push_measure(lua_State* L, double value) {
  if (std::isnan(value)) return 0;
  lua_pushnumber(L, value);
  return 1;
}

int w_FeaResult_index(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<FeaRecord> kept = check_fea_record(L, 1);
    const FeaRecord& record = *kept;
    const FeaResult& r = record.result;
    // Not lua_tostring: it would turn a number key into a string, which allocates.
    const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : nullptr;
    if (!key) return 0;
    auto is = [&](const char* name) { return std::strcmp(key, name) == 0; };
    lua_pushvalue(L, 1);  // the userdata, where push_cached_table keeps its tables
    return call_protected(L, 1, [&](lua_State* L) {
      if (is("export")) lua_pushcfunction(L, w_FeaResult_export);
      else if (is("status")) lua_pushstring(L, fea_status_name(r.status));
      else if (is("compression_only")) lua_pushboolean(L, r.compression_only);
      else if (is("iterations")) lua_pushinteger(L, r.iterations);
      else if (is("interior_point_iterations")) lua_pushinteger(L, r.interior_point_iterations);
      else if (is("max_displacement")) return push_measure(L, r.max_displacement);
      else if (is("max_penetration")) return push_measure(L, r.max_penetration);
      else if (is("total_weight")) lua_pushnumber(L, r.total_weight);
      else if (is("dofs")) lua_pushinteger(L, r.dofs);
      else if (is("element_count")) lua_pushinteger(L, static_cast<lua_Integer>(record.mesh->elements().size()));
      else if (is("factor_nonzeros")) lua_pushnumber(L, static_cast<double>(r.factor_nonzeros));
      else if (is("seconds")) lua_pushnumber(L, r.seconds);
      else if (is("nodes")) return push_cached_table(L, "nodes", record, push_nodes);
      else if (is("displacements")) return push_cached_table(L, "displacements", record, push_displacements);
      else if (is("elements")) return push_cached_table(L, "elements", record, push_elements);
      else if (is("element_blocks")) return push_cached_table(L, "element_blocks", record, push_element_blocks);
      else if (is("node_blocks")) return push_cached_table(L, "node_blocks", record, push_node_blocks);
      else if (is("contacts")) return push_cached_table(L, "contacts", record, push_contacts);
      else if (is("released")) return push_cached_table(L, "released", record, push_released);
      else if (is("interfaces")) return push_cached_table(L, "interfaces", record, push_interfaces);
      else if (is("history")) return push_cached_table(L, "history", record, push_history);
      else if (is("stresses")) {
        if (r.stresses.empty() && !record.mesh->elements().empty()) return 0;  // not asked for
        return push_cached_table(L, "stresses", record, push_stresses);
      } else return 0;
      return 1;
    });
  });
}

int w_FeaResult_tostring(lua_State* L) {
  if (push_if_closed<FeaRecord>(L, kFeaMeta, "FeaResult")) return 1;
  return guard(L, [&] {
    const std::shared_ptr<FeaRecord> record = check_fea_record(L, 1);
    const FeaResult& r = record->result;
    return call_protected(L, 0, [&](lua_State* L) {
      if (std::isnan(r.max_displacement)) {
        lua_pushfstring(L, "FeaResult (%s after %d iterations)", fea_status_name(r.status), r.iterations);
      } else {
        lua_pushfstring(L, "FeaResult (%s after %d iterations, max displacement %f m)",
                        fea_status_name(r.status), r.iterations, r.max_displacement);
      }
      return 1;
    });
  });
}

int w_FeaResult_gc(lua_State* L) { return release_boxed<FeaRecord>(L, kFeaMeta); }

}  // namespace

void register_FeaResult(lua_State* L) {
  // Fields are computed on access, so __index is a function, not a table.
  static const luaL_Reg metamethods[] = {{"__index", w_FeaResult_index},
                                         {"__tostring", w_FeaResult_tostring},
                                         {"__gc", w_FeaResult_gc},
                                         {"__close", w_FeaResult_gc},
                                         {nullptr, nullptr}};
  register_type(L, kFeaMeta, nullptr, metamethods);
}

void set_fea_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"fea", w_fea}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
