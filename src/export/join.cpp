#include "export/join.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/atomic_file.h"

extern char** environ;

namespace lodline {
namespace {

// ffmpeg's concat list quoting: '...' with each ' written as '\''.
std::string concatQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The frame number of "frame_NNNNN.ext", or -1.
long long frameNumber(const std::string& name, std::string& ext) {
  if (name.rfind("frame_", 0) != 0) return -1;
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos || dot <= 6) return -1;
  long long k = -1;
  auto [p, ec] = std::from_chars(name.data() + 6, name.data() + dot, k);
  if (ec != std::errc() || p != name.data() + dot) return -1;
  ext = name.substr(dot);
  return ext == ".png" || ext == ".svg" ? k : -1;
}

}  // namespace

Status joinVideos(std::span<const std::filesystem::path> parts, const std::filesystem::path& out) {
  if (parts.empty()) return Error::usage("join: give the parts to join");
  for (const auto& p : parts) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) return Error::runtime(p.string() + ": no such file");
    if (p.extension() != ".mp4") return Error::usage(p.string() + ": expected an .mp4 part");
  }
  const std::filesystem::path dir = out.parent_path().empty() ? std::filesystem::path(".") : out.parent_path();
  const std::string stem = "." + out.filename().string() + ".join" + std::to_string(getpid());
  const std::filesystem::path list = dir / (stem + ".txt"), tmp = dir / (stem + ".mp4"), log = dir / (stem + ".log");
  {
    std::ofstream l(list);
    for (const auto& p : parts) l << "file " << concatQuote(std::filesystem::absolute(p).string()) << '\n';
    if (!l) return Error::runtime(list.string() + ": cannot write the concat list");
  }
  const std::string list_s = list.string(), tmp_s = tmp.string();
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-v", "error", "-f", "concat", "-safe", "0", "-i", list_s,
                                   "-c", "copy", "-f", "mp4", "-movflags", "+faststart", "-y", tmp_s};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, "ffmpeg", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  std::error_code ec;
  if (rc != 0) {
    std::filesystem::remove(list, ec);
    std::filesystem::remove(log, ec);
    return Error::runtime(out.string() + ": ffmpeg not found (install Debian's ffmpeg)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string first_error;
  {
    std::ifstream in(log);
    std::getline(in, first_error);
  }
  std::filesystem::remove(list, ec);
  std::filesystem::remove(log, ec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !first_error.empty()) {
    std::filesystem::remove(tmp, ec);
    return Error::runtime(out.string() + ": ffmpeg could not join the parts" +
                          (first_error.empty() ? std::string() : ": " + first_error));
  }
  std::filesystem::rename(tmp, out, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return Error::runtime(out.string() + ": cannot write: " + ec.message());
  }
  return {};
}

Status joinFrameFolders(std::span<const std::filesystem::path> parts, const std::filesystem::path& out) {
  if (parts.empty()) return Error::usage("join: give the parts to join");
  // frame number → (part, file), checked before anything is copied.
  std::map<long long, std::filesystem::path> frames;
  std::string kind;
  for (const auto& part : parts) {
    std::error_code ec;
    if (!std::filesystem::is_directory(part, ec)) return Error::runtime(part.string() + ": not a folder of frames");
    size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(part, ec)) {
      std::string ext;
      const long long k = frameNumber(e.path().filename().string(), ext);
      if (k < 0) continue;
      if (!kind.empty() && ext != kind)
        return Error::usage(part.string() + ": holds " + ext + " frames, the other parts " + kind);
      kind = ext;
      if (auto [it, fresh] = frames.emplace(k, e.path()); !fresh)
        return Error::runtime(part.string() + ": frame " + std::to_string(k) + " is also in " +
                              it->second.parent_path().string());
      ++n;
    }
    if (ec) return Error::runtime(part.string() + ": cannot read: " + ec.message());
    if (n == 0) return Error::runtime(part.string() + ": no frame_NNNNN.png or .svg files");
  }
  long long expect = frames.begin()->first;
  for (const auto& [k, path] : frames) {
    if (k != expect)
      return Error::runtime(path.parent_path().string() + ": frames " + std::to_string(expect) + ".." +
                            std::to_string(k - 1) + " are in no part");
    ++expect;
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out)) return Error::runtime(out.string() + ": cannot create the folder");
  for (const auto& [k, path] : frames) {
    const std::filesystem::path to = out / path.filename();
    if (std::filesystem::equivalent(path.parent_path(), out, ec)) continue;
    const std::filesystem::path tmp = out / ("." + path.filename().string() + ".tmp" + std::to_string(getpid()));
    std::filesystem::copy_file(path, tmp, std::filesystem::copy_options::overwrite_existing, ec);
    if (!ec) std::filesystem::rename(tmp, to, ec);
    if (ec) {
      std::error_code ignore;
      std::filesystem::remove(tmp, ignore);
      return Error::runtime(to.string() + ": cannot write: " + ec.message());
    }
  }
  return {};
}

Status joinMetricsCsv(std::span<const std::filesystem::path> parts, const std::filesystem::path& out) {
  if (parts.empty()) return Error::usage("join: give the parts to join");
  std::string header;
  std::map<long long, std::pair<std::string, std::filesystem::path>> rows;
  for (const auto& part : parts) {
    std::ifstream in(part);
    if (!in) return Error::runtime(part.string() + ": cannot open for reading");
    std::string h;
    if (!std::getline(in, h) || h.rfind("frame,", 0) != 0)
      return Error::runtime(part.string() + ": not a capture metrics CSV (its first line must start with 'frame,')");
    if (header.empty()) header = h;
    else if (h != header)
      return Error::runtime(part.string() + ": its columns differ from " + parts[0].string() + "'s");
    size_t line_no = 1;
    for (std::string line; std::getline(in, line);) {
      ++line_no;
      if (line.empty()) continue;
      long long k = -1;
      const size_t comma = line.find(',');
      auto [p, ec] = std::from_chars(line.data(), line.data() + std::min(comma, line.size()), k);
      if (ec != std::errc() || k < 0 || comma == std::string::npos)
        return Error::runtime(part.string() + ": line " + std::to_string(line_no) + ": no frame number");
      if (auto [it, fresh] = rows.emplace(k, std::make_pair(line, part)); !fresh)
        return Error::runtime(part.string() + ": frame " + std::to_string(k) + " is also in " + it->second.second.string());
    }
  }
  if (rows.empty()) return Error::runtime(parts[0].string() + ": no frames in any part");
  long long expect = rows.begin()->first;
  std::ostringstream csv;
  csv << header << '\n';
  for (const auto& [k, row] : rows) {
    if (k != expect)
      return Error::runtime(row.second.string() + ": frames " + std::to_string(expect) + ".." + std::to_string(k - 1) +
                            " are in no part");
    ++expect;
    csv << row.first << '\n';
  }
  const std::string text = csv.str();
  return writeFileAtomically(out, [&](std::ostream& o) -> Status {
    o << text;
    return {};
  });
}

}  // namespace lodline
