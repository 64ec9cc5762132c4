// `ashlar test [--update] [folder [name ...]]`: runs a folder of check
// scripts, each in a fresh Lua state set up as the host's, compares what
// they record (regression_check.hpp) with the folder's golden file
// (regression_golden.hpp), and prints a line per failure, then
// "N passed, N failed". With --update it rewrites the golden file.
#pragma once

#include <cstdio>

namespace ashlar::regression {

// argv[0] is the program, argv[1] "test". Returns the exit status: 0 only
// when every check passed.
int run_regression_command(int argc, char** argv);

// The usage lines of the command, for the host's help too.
void print_test_usage(FILE* out);

}  // namespace ashlar::regression
