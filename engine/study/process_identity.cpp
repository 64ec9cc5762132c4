#include "study/process_identity.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <signal.h>
#include <sstream>
#include <unistd.h>

namespace ashlar::study {

namespace {

std::string first_line(const char* path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// Field 22 of /proc/<pid>/stat (after the command, which may hold spaces
// and parentheses, so counted from the last ')'); 0 when unreadable.
std::int64_t start_ticks(std::int64_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(text.substr(close + 1));
  std::string field;
  for (int index = 3; index <= 22 && fields >> field; ++index)
    if (index == 22) return std::strtoll(field.c_str(), nullptr, 10);
  return 0;
}

ProcessIdentity identify() {
  ProcessIdentity self;
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) == 0) self.host = host;
  self.pid = static_cast<std::int64_t>(getpid());
  self.started = start_ticks(self.pid);
  const std::string boot = first_line("/proc/sys/kernel/random/boot_id");
  char space[256] = {};
  const ssize_t length = readlink("/proc/self/ns/pid", space, sizeof space - 1);
  if (!boot.empty() && length > 0) self.machine = boot + " " + std::string(space, static_cast<std::size_t>(length));
  return self;
}

}  // namespace

const ProcessIdentity& this_process() {
  static const ProcessIdentity self = identify();
  return self;
}

bool has_ended(const ProcessIdentity& other) {
  const ProcessIdentity& self = this_process();
  if (self.host.empty() || self.machine.empty() || other.host != self.host || other.machine != self.machine ||
      other.pid <= 0)
    return false;
  if (kill(static_cast<pid_t>(other.pid), 0) != 0 && errno == ESRCH) return true;
  // A process with that pid exists (EPERM: another user's): the same one
  // only if it started when the run's process did.
  const std::int64_t started = start_ticks(other.pid);  // 0: unreadable (hidepid) or just gone
  return other.started != 0 && started != 0 && started != other.started;
}

}  // namespace ashlar::study
