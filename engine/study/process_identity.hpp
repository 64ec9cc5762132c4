// Who a process is, well enough for processes that share a study database
// to tell whether a run's process has ended: on the same machine (same host
// name, boot and pid namespace) a process is gone when no process has its
// pid and its start time. On other machines nothing can be told from here:
// only the run's heartbeat (study_claims) says it is alive.
#pragma once

#include <cstdint>
#include <string>

namespace ashlar::study {

struct ProcessIdentity {
  std::string host;         // host name
  std::string machine;      // boot id and pid namespace; empty when unknown
  std::int64_t pid = 0;
  std::int64_t started = 0;  // start time in clock ticks after boot; 0 when unknown
};

// The calling process.
const ProcessIdentity& this_process();

// True only when `other` is known to have ended: it ran on this machine
// (same host and machine, both known) and no process with its pid and start
// time exists. False when it may still run, or when it cannot be told.
bool has_ended(const ProcessIdentity& other);

}  // namespace ashlar::study
