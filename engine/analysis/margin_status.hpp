// How a search for a margin ended: the load factor, the friction demand
// (load_factor.hpp), the load capacity (load_capacity.hpp), and their
// kinematic versions (kinematic.hpp). One vocabulary for all of them: the
// kinematic searches start from the equilibrium method's answers and pass
// their outcomes on, and Clp's failures can end any of them.
#pragma once

#include "core/enum_names.hpp"

namespace ashlar {

// Each result says which of these it can end with, and what its numbers
// and its verdict (`stable`) are then: a stopped search, a failed solver or
// an analysis that did not settle decides nothing it had not decided before.
enum class MarginStatus {
  optimal,                 // the answer
  unbounded,               // no multiple of the load is too much; a kinematic
                           // friction demand: it stands only without sliding
  infeasible,              // no multiple of the load lets it stand
  unstable,                // it does not stand even without the load, or without sliding
  floating,                // a free block has no contact path to a support
  stopped,                 // Clp's iteration limit
  numerical_difficulties,  // Clp's
  unexpected,              // a Clp status that none of the others covers
  no_verdict,              // a kinematic analysis did not settle
  interrupted,             // Ctrl-C or a sandbox deadline
};
// The names scripts see (r.status). Three keep their spaces, unlike other
// enums' names: scripts compare these strings.
inline constexpr EnumNames<MarginStatus, 10> kMarginStatusNames{
    {{{MarginStatus::optimal, "optimal"},
      {MarginStatus::unbounded, "unbounded"},
      {MarginStatus::infeasible, "infeasible"},
      {MarginStatus::unstable, "unstable"},
      {MarginStatus::floating, "floating"},
      {MarginStatus::stopped, "stopped"},
      {MarginStatus::numerical_difficulties, "numerical difficulties"},
      {MarginStatus::unexpected, "unexpected simplex status"},
      {MarginStatus::no_verdict, "no verdict"},
      {MarginStatus::interrupted, "interrupted"}}}};

}  // namespace ashlar
