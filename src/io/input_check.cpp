#include "io/input_check.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lodline {

Status checkInputFile(const std::filesystem::path& path, const std::string& what) {
  const std::string name = path.string();
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return Error::runtime(name + ": no such file");
    return Error::runtime(name + ": cannot open for reading: " + std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) return Error::runtime(name + ": is a directory, not a " + what);
  if (!S_ISREG(st.st_mode))
    return Error::runtime(name + ": is not a regular file (a FIFO, device or socket), not a " + what);
  // A regular file: open() does not block. O_NOFOLLOW is not wanted (symlinks are fine).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error::runtime(name + ": cannot open for reading: " + std::strerror(errno));
  ::close(fd);
  return {};
}

}  // namespace lodline
