#include "scene/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace granvv::app {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int err) {
  throw std::runtime_error("cannot " + what + " " + path.string() + ": " + std::strerror(err));
}

// Writes all of text to fd, retrying short writes and EINTR; returns 0 or the errno.
int write_all(int fd, const std::string& text) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

}  // namespace

void sync_to_disk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("open", path, errno);
  const int synced = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // A folder on a file system that cannot sync folders (EINVAL) is no failure of ours.
  if (synced != 0 && err != EINVAL) fail("flush", path, err);
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".partial";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("create", tmp, errno);
  int err = write_all(fd, text);
  const char* step = "write";
  if (err == 0 && ::fsync(fd) != 0) err = errno, step = "flush";
  if (::close(fd) != 0 && err == 0) err = errno, step = "close";
  if (err == 0 && ::rename(tmp.c_str(), path.c_str()) != 0) err = errno, step = "rename";
  if (err != 0) {
    ::unlink(tmp.c_str());
    fail(step, step == std::string("rename") ? path : tmp, err);
  }
}

}  // namespace granvv::app
