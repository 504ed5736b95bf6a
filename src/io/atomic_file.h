#pragma once
// Writing a whole file through `path.tmp` and a rename, with POSIX calls so that a failure
// reports its errno (a full disk says "No space left on device", a size limit "File too
// large"). Header-only: the renderer (PNG files) and the io library both use it.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sluice {

// Thrown when an output file cannot be written; the message names the path and the cause.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `size` bytes to `path` through `path.tmp` and a rename: an existing `path` is
// either the old complete file or the new complete one, and no `path.tmp` stays behind
// after a failure. Throws OutputError.
inline void write_bytes_atomic(const std::string& path, const void* data, std::size_t size) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(path + ": cannot open " + tmp + " for writing: " + std::strerror(errno));
  const char* p = static_cast<const char*>(data);
  int err = 0;
  for (std::size_t left = size; left > 0 && err == 0;) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      err = n < 0 ? errno : ENOSPC;
    else {
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw OutputError(path + ": write failed: " + std::strerror(err));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    ::unlink(tmp.c_str());
    throw OutputError(path + ": cannot rename " + tmp + " to it: " + std::strerror(err));
  }
}

}  // namespace sluice
