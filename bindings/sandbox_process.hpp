// The `ashlar --sandbox` command line: its options, and the limits that only
// a process of its own can set (see sandbox.hpp for those of the state).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "sandbox.hpp"

namespace ashlar::sandbox {

constexpr double kDefaultSeconds = 600;
constexpr const char* kDefaultOutputFolder = "out";

// What `--sandbox` and the options beside it asked for.
struct ProcessOptions {
  ProcessOptions() { settings.seconds = kDefaultSeconds; }
  bool enabled = false;
  Settings settings;
  bool folders_given = false;  // any --read or --write
  // Memory the whole process (engine included) may add to what it holds at
  // start, enforced as RLIMIT_DATA; 0: no limit.
  std::size_t engine_memory_bytes = std::size_t{4} << 30;
};

// Command-line values, also `ashlar test`'s: a whole number >= 0 ("1e9"
// too), a number of seconds >= 0. False when `text` is not one.
bool parse_count(const char* text, std::uint64_t& count);
bool parse_seconds(const char* text, double& seconds);

// Whether `option` is a sandbox option followed by a value (--read DIR, ...).
bool takes_value(const char* option);

// Reads one sandbox option at argv[i] (advancing i past its value). Returns
// false when argv[i] is not a sandbox option; sets `error` when it is one
// but its value is wrong.
bool parse_option(int argc, char** argv, int& i, ProcessOptions& options, std::string& error);

// Completes the settings for `script` (nullptr: stdin or -e chunks): the
// script's folder (else the current folder) is the base folder and, unless
// folders were given, the folder to read, and its subfolder out (created)
// the folder to write. Throws ashlar::Error.
void complete_settings(ProcessOptions& options, const char* script);

// Caps the process's data segment and starts the hard deadline: past the
// time limit and a grace period, a script stuck in C code ends the process
// with a message. Throws ashlar::Error when the limit cannot be set.
void limit_process(const ProcessOptions& options);

}  // namespace ashlar::sandbox
