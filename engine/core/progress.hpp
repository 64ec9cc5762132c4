// How far a long computation has got, for a progress line: called on the
// calling thread with (units done, units in all), first with 0 done, then
// as units are done. The units are the computation's own: blocks for the
// per-block analyses (load capacity, important weights), digits of the
// bracket for the friction demand's search, the solver's iterations for a
// single program (load factor), whose count is not known ahead: its total
// is kTotalUnknown.
#pragma once

#include <functional>

namespace ashlar {

using ProgressCount = std::function<void(int done, int total)>;
constexpr int kTotalUnknown = -1;

}  // namespace ashlar
