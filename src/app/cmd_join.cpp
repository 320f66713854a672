// `lodline join PART... -o OUT`: joins the outputs of a capture rendered in shards
// (`capture --frames A:B`): MP4s without re-encoding, folders of frame PNGs or SVGs, or the
// metrics CSVs; OUT's form says which (docs/capture.md). Parses, then export/join.h joins.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "export/join.h"
#include "io/atomic_file.h"

namespace lodline {
namespace {

struct JoinOptions {
  std::vector<std::string> parts;
  std::string output;
};

int runJoin(const JoinOptions& o) {
  if (o.parts.empty()) return reportError(Error::usage("join: give the parts to join (PART... -o OUT)"));
  std::vector<std::filesystem::path> parts(o.parts.begin(), o.parts.end());
  const std::filesystem::path out(o.output);
  const std::string ext = out.extension().string();
  const bool folder = o.output.back() == '/' || std::filesystem::is_directory(out);
  Status s;
  if (folder) {
    s = joinFrameFolders(parts, out);
  } else if (ext == ".mp4" || ext == ".csv") {
    if (Status w = checkWritable(out); !w) return reportError(w.error());
    s = ext == ".mp4" ? joinVideos(parts, out) : joinMetricsCsv(parts, out);
  } else {
    return reportError(Error::usage("-o: expected OUT.mp4, OUT.csv or a folder DIR/, got '" + o.output + "'"));
  }
  if (!s) return reportError(s.error());
  return 0;
}

}  // namespace

Command addJoinCommand(CLI::App& parent) {
  auto o = std::make_shared<JoinOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "join", "Join the outputs of capture shards (--frames A:B): MP4s (no re-encoding), frame folders or metrics CSVs");
  cmd->add_option("parts", o->parts, "The shards' outputs: .mp4 files in frame order, frame folders, or --metrics CSVs")
      ->required();
  cmd->add_option("-o,--output", o->output,
                  "OUT.mp4 (ffmpeg's concat demuxer, stream copy), DIR/ (frame_NNNNN.png or .svg copied; frames must "
                  "not repeat or leave gaps) or OUT.csv (rows by frame; the same columns in every part)")
      ->required();
  return {cmd, [o] { return runJoin(*o); }};
}

}  // namespace lodline
