#include "io/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <system_error>

#include <unistd.h>

namespace lodline {
namespace {

std::filesystem::path directoryOf(const std::filesystem::path& path) {
  const auto dir = path.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

}  // namespace

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
    result = write(out);
    out.flush();
    if (result && !out.good())
      result = Error::runtime(path.string() + ": write failed (disk full?)");
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
