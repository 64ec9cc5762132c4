// ashlar.load_factor and ashlar.friction_demand: how far a structure is
// from collapse.
#pragma once

#include <lua.hpp>

#include <optional>
#include <vector>

#include <memory>
#include <string>

#include "analysis/equilibrium.hpp"
#include "analysis/load_factor.hpp"
#include "luax.hpp"

namespace ashlar::lua {

// A result of ashlar.load_factor (the equilibrium method's) read back from
// its table: what draws the structure at its limit.
struct LoadFactorRecord {
  LoadFactorSettings settings;  // the load pattern, direction and friction it had
  double factor = 0.0;
  std::vector<BlockMotion> mechanism;
  std::vector<LimitInterface> limit;
};

// The table at stack index idx (inside argument `arg`, named `what` in
// errors) as a load factor's result, or nothing when it is not a table with
// a `factor` and a `load` (then it is no load factor's result). Raises an
// ArgError for a damaged one (a missing mechanism, a bad limit entry).
std::optional<LoadFactorRecord> to_load_factor(lua_State* L, int idx, int arg, const std::string& what);

// What the `result` option of ashlar.draw and ashlar.export holds: an
// analysis (with its own mechanism and limit when it has them), or a load
// factor's result, whose structure at the factor (structure_at_factor) the
// engine analyses for the equilibrium at the limit.
struct ResultOption {
  std::shared_ptr<const EquilibriumResult> analysis;
  std::optional<LoadFactorRecord> factor;
  // The mechanism's limit interfaces and block motions; null when there is none.
  const std::vector<LimitInterface>* limit() const;
  const std::vector<BlockMotion>* mechanism() const;
};

// Reads the `result` option: a Result of ashlar.analyze, a result of
// ashlar.load_factor (analysed at its factor with `contact`), or nothing.
ResultOption result_with_mechanism(lua_State* L, const OptionTable& options, const Structure& s,
                                   const ContactOptions& contact);

// Sets the functions into the table on top of the stack.
void set_margin_functions(lua_State* L);

}  // namespace ashlar::lua
