#include "io/atomic_file.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <random>
#include <system_error>

#include <sys/types.h>
#include <unistd.h>

namespace lodline {
namespace {

std::filesystem::path directoryOf(const std::filesystem::path& path) {
  const auto dir = path.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

// The process id written after `prefix` in `name` (digits, then `stop`); 0 if there is none.
pid_t pidAfter(const std::string& name, const std::string& prefix, char stop) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  long long pid = 0;
  size_t i = prefix.size();
  for (; i < name.size() && name[i] >= '0' && name[i] <= '9' && pid < (1ll << 31); ++i) pid = pid * 10 + (name[i] - '0');
  if (i == prefix.size() || i >= name.size() || name[i] != stop) return 0;
  return static_cast<pid_t>(pid);
}

bool processExists(pid_t pid) { return kill(pid, 0) == 0 || errno == EPERM; }

}  // namespace

void removeStaleTemporaries(const std::filesystem::path& path) {
  const std::string file = path.filename().string();
  if (file.empty()) return;
  std::string tmp_prefix(".");  // append(): see writeFileAtomically on GCC 12's -Wrestrict
  tmp_prefix.append(file).append(".tmp");
  std::string part_prefix(".");
  part_prefix.append(file).append(".part");
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directoryOf(path), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    pid_t pid = pidAfter(name, tmp_prefix, '-');
    if (pid == 0) pid = pidAfter(name, part_prefix, '.');
    if (pid <= 0 || pid == getpid() || processExists(pid)) continue;
    std::error_code ignored;
    std::filesystem::remove(it->path(), ignored);
  }
}

Status checkWritable(const std::filesystem::path& path) {
  const auto dir = directoryOf(path);
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    return Error::runtime(path.string() + ": cannot write: directory '" + dir.string() +
                          "' does not exist");
  if (std::filesystem::is_directory(path, ec))
    return Error::runtime(path.string() + ": cannot write: it is a directory");
  if (access(dir.c_str(), W_OK) != 0)
    return Error::runtime(path.string() + ": cannot write: " + std::strerror(errno));
  return {};
}

Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(std::ostream&)>& write) {
  if (Status s = checkWritable(path); !s) return s;
  removeStaleTemporaries(path);
  std::random_device rd;
  // Built with append(): GCC 12 warns falsely (-Wrestrict, PR 105329) on "." + std::string.
  std::string tmp_name(".");
  tmp_name.append(path.filename().string()).append(".tmp").append(std::to_string(getpid()));
  tmp_name.append("-").append(std::to_string(rd() & 0xffffff));
  const auto tmp = directoryOf(path) / tmp_name;
  Status result;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return Error::runtime(path.string() + ": cannot write: " + std::strerror(errno));
    errno = 0;
    result = write(out);
    if (out.good()) out.flush();
    if (result && out.good()) out.close();  // close() writes what is still buffered
    if (result && out.fail()) {
      const int err = errno;  // ENOSPC, EFBIG, EIO... left by the failed write (best effort)
      result = Error::runtime(path.string() + ": write failed: " +
                              (err != 0 ? std::string(std::strerror(err)) : std::string("disk full?")));
    }
  }
  std::error_code ec;
  if (!result) {
    std::filesystem::remove(tmp, ec);
    return result;
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return Error::runtime(path.string() + ": cannot write: " + ec.message());
  }
  return {};
}

}  // namespace lodline
