// The parts of `lodline sweep` (cmd_sweep.cpp runs the renders): the plan of runs, checked
// before anything renders (sweep_plan.cpp), and the summaries of their results: results.csv,
// contact sheets, charts (sweep_outputs.cpp). docs/experiments.md describes the outputs.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/result.h"
#include "export/text.h"

namespace lodline::sweep {

/// One --vary list.
struct Axis {
  std::string key;                  ///< render option without dashes, view.az / view.el / view.dist, or model
  std::vector<std::string> values;  ///< as given; an empty value passes no option (render's default)
};

struct Run {
  std::string name;                 ///< file-name stem made of the varied values
  std::string model;                ///< MODEL, or this run's value of --vary model
  std::vector<size_t> index;        ///< value index per axis
  std::vector<std::string> args;    ///< render options of this run (besides MODEL, -o, --stats)
  std::filesystem::path cache_dir;  ///< where its progressive mesh is cached
};

struct Plan {
  std::string model;               ///< MODEL; empty when the model is varied (each Run has its own)
  bool zip = false;                ///< runs pair the lists instead of crossing them
  std::vector<Axis> axes;
  std::vector<std::string> fixed;  ///< render options of every run (--set, then those after --)
  /// The fixed options as given (--set KEY=VALUE as --KEY=VALUE, view.* parts included; `fixed`
  /// folds those into each run's --view): for titles and for recognising the same sweep.
  std::vector<std::string> fixed_given;
  std::vector<Run> runs;           ///< cross product with the first axis slowest, or the pairs
};

/// The command-line input of a plan.
struct PlanOptions {
  std::string model;                     ///< MODEL; empty with --vary model=A,B,...
  std::vector<std::string> vary;         ///< KEY=V1,V2,... (split at ';' when the list holds one)
  std::vector<std::string> set;          ///< KEY=VALUE
  std::vector<std::string> passthrough;  ///< render options after `--`
  bool zip = false;
};

/// Builds the runs and checks every run's options as `lodline render` would (its own option
/// parser, then the functions it resolves values with; detail maps are read), without
/// rendering. Errors name the bad key or value (usage errors, exit code 2; a missing file is a
/// runtime error). Does not look at the model file.
Result<Plan> makePlan(const PlanOptions& options);

/// "KEY-VALUE" with the value kept when it is made of [A-Za-z0-9.+-] only; otherwise its
/// safe characters (a path's file stem) and a hash of the exact value: unique and stable.
std::string namePart(const std::string& key, const std::string& value);

/// `s` as a finite number, if all of it is one.
std::optional<double> parseNumber(const std::string& s);

enum class RunState {
  kPending,      ///< to render
  kComplete,     ///< its PNG and JSON were there before this sweep started (skipped)
  kRendered,     ///< rendered now
  kFailed,       ///< render failed (error recorded)
  kInterrupted,  ///< stopped by Ctrl-C (outputs removed)
};

struct RunResult {
  RunState state = RunState::kPending;
  std::string error;     ///< why it failed
  nlohmann::json stats;  ///< its stats JSON when complete or rendered
};

inline bool hasStats(const RunResult& r) { return r.state == RunState::kComplete || r.state == RunState::kRendered; }
/// Runs that get a row in results.csv: done or failed.
inline bool hasResult(const RunResult& r) { return hasStats(r) || r.state == RunState::kFailed; }

inline std::filesystem::path pngOf(const std::filesystem::path& runs_dir, const Run& r) {
  return runs_dir / (r.name + ".png");
}
inline std::filesystem::path jsonOf(const std::filesystem::path& runs_dir, const Run& r) {
  return runs_dir / (r.name + ".json");
}

/// Names of the result columns read from the stats JSON, in results.csv order.
std::vector<std::string> statColumnNames();
bool isStatColumn(const std::string& name);

/// results.csv: run, the varied keys, status, error, then the stat columns; one row per run
/// with a result, in plan order. Written atomically.
Status writeResultsCsv(const std::filesystem::path& path, const Plan& plan, const std::vector<RunResult>& results);

struct SheetOptions {
  std::string title;                  ///< first title line; empty = the model and the axes
  std::vector<std::string> captions;  ///< columns printed under each cell
  int cell_width = 0;                 ///< px; 0 = the first render's width, at most 320
  /// Cells per row of a --zip sheet; 0 = all in one row up to 5 runs, else a square.
  int columns = 0;
};

/// Contact sheets in `dir`: sheet.png, or one sheet_KEY-VALUE....png per combination of the
/// third and later axes. Renders are read from `runs_dir`. Returns the files written.
Result<std::vector<std::filesystem::path>> writeSheets(const Plan& plan, const std::vector<RunResult>& results,
                                                       const std::filesystem::path& dir,
                                                       const std::filesystem::path& runs_dir, const Font& font,
                                                       const SheetOptions& options);

/// chart_COLUMN.svg in `dir` for each stat column in `columns`: the column against the first
/// axis, one line per combination of the other axes' values. Returns the files written.
Result<std::vector<std::filesystem::path>> writeCharts(const Plan& plan, const std::vector<RunResult>& results,
                                                       const std::filesystem::path& dir,
                                                       const std::vector<std::string>& columns);

}  // namespace lodline::sweep
