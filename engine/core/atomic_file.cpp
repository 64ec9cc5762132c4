// Whole-or-nothing writes with POSIX calls: the data goes to a fresh file
// beside the target (same file system, so rename() is atomic), is fsync'ed,
// then renamed over the target. A reader sees the old file or the new one,
// never a part; a crash leaves at most a stray "<name>.tmp<pid>-<n>" file.
#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <utility>

#include "core/error.hpp"

namespace ashlar {
namespace {

std::string describe_errno(int error_number) { return std::strerror(error_number); }

std::string parent_folder(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// Writes all of `contents` to `fd`, retrying short writes and EINTR.
bool write_all(int fd, const std::string& contents) {
  const char* data = contents.data();
  size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    left -= static_cast<size_t>(written);
  }
  return true;
}

// Opens a new file beside `path` under a name no one else uses (process id
// and a counter; EEXIST means a leftover, so the next name is tried). Mode
// 0666 lets the kernel apply the umask, as for any file the user creates
// (mkstemp would make it 0600, and reading the umask means changing it,
// which races with other threads).
int create_temporary(const std::string& path, std::string& temp_path) {
  static std::atomic<unsigned long> counter{0};
  for (int attempt = 0; attempt < 1000; ++attempt) {
    temp_path = path + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const int fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// Makes the rename itself durable; failure here does not undo the write, so
// it is not reported.
void sync_folder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

StagedFile::StagedFile(std::string path, const std::string& contents) : path_(std::move(path)) {
  if (path_.empty()) throw IoError("cannot write a file with an empty path");
  std::string temp_path;
  const int fd = create_temporary(path_, temp_path);
  if (fd < 0) throw IoError("cannot write '" + path_ + "': " + describe_errno(errno));
  auto fail = [&](const std::string& step, bool open) {
    const int error_number = errno;
    if (open) ::close(fd);
    ::unlink(temp_path.c_str());
    throw IoError("cannot write '" + path_ + "' (" + step + "): " + describe_errno(error_number));
  };
  if (!write_all(fd, contents)) fail("write", true);
  if (::fsync(fd) != 0) fail("fsync", true);
  if (::close(fd) != 0) fail("close", false);
  temp_path_ = std::move(temp_path);
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), temp_path_(std::move(other.temp_path_)) {
  other.temp_path_.clear();
}

StagedFile::~StagedFile() {
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
}

void StagedFile::commit() {
  if (temp_path_.empty()) throw IoError("cannot write '" + path_ + "': already committed");
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    throw IoError("cannot write '" + path_ + "' (rename): " + describe_errno(errno));
  }
  temp_path_.clear();
  sync_folder(parent_folder(path_));
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  StagedFile(path, contents).commit();
}

std::string read_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw IoError("cannot read '" + path + "': " + describe_errno(errno));
  struct stat info {};
  if (::fstat(fd, &info) == 0 && S_ISDIR(info.st_mode)) {
    ::close(fd);
    throw IoError("cannot read '" + path + "': it is a folder");
  }
  std::string contents;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, chunk, sizeof chunk);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      const int error_number = errno;
      ::close(fd);
      throw IoError("cannot read '" + path + "': " + describe_errno(error_number));
    }
    contents.append(chunk, static_cast<size_t>(got));
  }
  ::close(fd);
  return contents;
}

}  // namespace ashlar
