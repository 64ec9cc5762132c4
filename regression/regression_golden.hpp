// The golden values of a regression suite: one JSON file per folder, keyed
// by script file name and then check name, e.g.
//   { "arch.lua": { "t/R, 16 voussoirs": 0.10707622829246521 } }
// laid out for diffs: keys sorted, one value per line (each number of a list
// too), numbers with 17 significant digits so that they read back exactly.
#pragma once

#include <map>
#include <string>

#include "regression_check.hpp"

namespace ashlar::regression {

using ScriptGolden = std::map<std::string, Value>;         // by check name
using GoldenValues = std::map<std::string, ScriptGolden>;  // by script file name

// The file at `path`, or no values when there is no such file. Throws
// std::runtime_error naming the path and what is wrong (syntax with line and
// column, or a value of a kind that checks cannot record).
GoldenValues read_golden_file(const std::string& path);

// The file's text for `values` (scripts without values left out).
std::string format_golden_file(const GoldenValues& values);

}  // namespace ashlar::regression
