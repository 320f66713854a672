// `lodline sweep MODEL --vary KEY=V1,V2,... -o DIR`: renders every combination of the varied
// render options (or the paired lists with --zip) as child processes `lodline render`, and
// gathers their stats into results.csv, contact sheets and line charts (docs/experiments.md).
// Runs are named after their values, so a rerun keeps completed runs and renders the rest.
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <poll.h>
#include <unistd.h>

#include "app/child_process.h"
#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "app/sweep.h"
#include "core/timer.h"
#include "export/text.h"
#include "io/atomic_file.h"
#include "io/scene_file.h"

namespace lodline {
namespace {

using namespace sweep;

// Set by SIGINT/SIGTERM: no new runs start, running ones are stopped, and the summaries are
// written for the runs done. (Signal handlers can only reach process-wide state.)
std::atomic<bool> g_sweep_interrupted{false};
extern "C" void onSweepInterrupt(int) { g_sweep_interrupted.store(true); }

struct SweepOptions {
  PlanOptions plan;      ///< model, --vary, --set, --zip, options after --
  std::string output;    ///< the sweep directory
  int jobs = 1;          ///< renders at the same time
  bool force = false;    ///< render complete runs again
  bool dry_run = false;  ///< check and print the plan only
  /// Print one self-contained shell command per pending run (for GNU parallel, a Slurm
  /// array, any scheduler) instead of rendering.
  bool emit_commands = false;
  /// Render nothing: gather the runs already in the directory (rendered elsewhere) into
  /// results.csv, the sheets and the charts.
  bool collect = false;
  std::vector<std::string> charts;  ///< stat columns to plot
  SheetOptions sheet;
  std::string font = kDefaultFontPath;
  // Render options given directly (sweep MODEL --size 320x240 ...): parsed here only to be
  // passed on to every run, as if they followed `--`.
  ViewOptions render_view;
  DetailOptions render_detail;
  std::vector<const CLI::Option*> render_options;
};

// The render options given on the sweep's command line, as render arguments, in the order
// the options were declared.
std::vector<std::string> givenRenderOptions(const std::vector<const CLI::Option*>& options) {
  std::vector<std::string> out;
  for (const CLI::Option* opt : options) {
    if (opt->count() == 0) continue;
    const std::string name = "--" + opt->get_single_name();
    if (opt->get_type_size() == 0) {  // a flag
      out.push_back(name);
      continue;
    }
    for (const std::string& v : opt->results()) out.push_back(name + "=" + v);
  }
  return out;
}

std::string shellQuote(const std::string& s) {
  if (!s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("-_.,/=+:@%^").find(c) != std::string_view::npos;
      }))
    return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Removes what a child that was stopped or failed may have left: its outputs and the
// temporary files of its atomic writes (".NAME.tmpPID-..."), here and in its cache directory.
void cleanUpAfter(const std::filesystem::path& runs_dir, const Run& run, pid_t pid, bool outputs) {
  std::error_code ec;
  if (outputs) {
    std::filesystem::remove(pngOf(runs_dir, run), ec);
    std::filesystem::remove(jsonOf(runs_dir, run), ec);
  }
  const std::string tag = ".tmp" + std::to_string(pid) + "-";
  for (const auto& dir : {runs_dir, run.cache_dir}) {
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string f = it->path().filename().string();
      if (!f.empty() && f[0] == '.' && f.find(tag) != std::string::npos) std::filesystem::remove(it->path(), ec);
    }
  }
}

// The child's error: its last "lodline: ..." line, else its last line.
std::string errorOf(const ChildExit& e) {
  std::string last, last_error;
  std::istringstream in(e.output);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    last = line;
    if (line.rfind("lodline: ", 0) == 0) last_error = line.substr(9);
  }
  if (!last_error.empty()) return last_error;
  if (e.signal) return "killed by signal " + std::to_string(e.signal) + " (" + strsignal(e.signal) + ")";
  if (!last.empty()) return last;
  return "exit status " + std::to_string(e.code);
}

void drawProgress(size_t done, size_t total, size_t failed, double elapsed_ms) {
  const int width = 30;
  const double f = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const int filled = static_cast<int>(f * width);
  const double eta_s = done ? elapsed_ms / static_cast<double>(done) * static_cast<double>(total - done) / 1000.0 : 0.0;
  std::fprintf(stderr, "\r  run %zu/%zu [%s%s] %3d%%  ETA %dm%02ds", done, total, std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), static_cast<int>(f * 100.0), static_cast<int>(eta_s) / 60,
               static_cast<int>(eta_s) % 60);
  if (failed) std::fprintf(stderr, "  %zu failed", failed);
  std::fputs("\033[K", stderr);
  std::fflush(stderr);
}

struct Active {
  size_t run;
  ChildProcess child;
};

// Renders the pending runs, `jobs` at a time; fills `results`. Returns false if interrupted.
bool executeRuns(const std::string& exe, const std::vector<Run>& runs,
                 const std::filesystem::path& runs_dir, int jobs, std::vector<RunResult>& results) {
  std::vector<size_t> pending;
  for (size_t i = 0; i < runs.size(); ++i)
    if (results[i].state == RunState::kPending) pending.push_back(i);
  // With nothing rendered yet, the first run goes alone, so it builds the progressive-mesh
  // cache once instead of every job building it at the same time.
  const bool warm_up = jobs > 1 && std::none_of(results.begin(), results.end(), [](const RunResult& r) {
                         return r.state == RunState::kComplete;
                       });
  const bool tty = isatty(STDERR_FILENO);
  std::vector<Active> active;
  size_t next = 0, finished = 0, failed = 0;
  bool stopping = false;
  Stopwatch wall;
  if (tty && !pending.empty()) drawProgress(0, pending.size(), 0, 0.0);
  while (true) {
    if (g_sweep_interrupted.load() && !stopping) {
      stopping = true;
      for (const auto& a : active) a.child.signal(SIGTERM);
    }
    while (!stopping && next < pending.size() && active.size() < static_cast<size_t>(jobs) &&
           !(warm_up && finished == 0 && !active.empty())) {
      const size_t i = pending[next++];
      const Run& run = runs[i];
      // A run is rendered from scratch: an old PNG or JSON must not outlive a failure.
      std::error_code ec;
      std::filesystem::remove(pngOf(runs_dir, run), ec);
      std::filesystem::remove(jsonOf(runs_dir, run), ec);
      std::vector<std::string> args = {"render", run.model};
      args.insert(args.end(), run.args.begin(), run.args.end());
      for (const std::string& s : {std::string("-o"), pngOf(runs_dir, run).string(), std::string("--stats"),
                                   jsonOf(runs_dir, run).string()})
        args.push_back(s);
      auto child = ChildProcess::spawn(exe, args);
      if (!child) {
        results[i] = {RunState::kFailed, child.error().message, {}};
        ++finished;
        ++failed;
        if (tty) std::fputs("\r\033[K", stderr);
        std::cerr << "lodline: sweep: run " << run.name << " failed: " << results[i].error << '\n';
        continue;
      }
      active.push_back({i, std::move(child.value())});
    }
    if (active.empty()) break;
    std::vector<pollfd> fds;
    for (const auto& a : active) fds.push_back({a.child.fd(), POLLIN, 0});
    poll(fds.data(), fds.size(), 250);  // EINTR: the flag is checked at the top
    for (size_t k = active.size(); k-- > 0;) {
      if (active[k].child.readAvailable()) continue;
      const size_t i = active[k].run;
      const pid_t pid = active[k].child.pid();
      const ChildExit e = active[k].child.wait();
      active.erase(active.begin() + static_cast<std::ptrdiff_t>(k));
      const Run& run = runs[i];
      std::error_code ec;
      // Both outputs written (the JSON last, each atomically): complete, even when the stop
      // signal reached the child after its last write.
      const bool written = std::filesystem::exists(pngOf(runs_dir, run), ec) &&
                           std::filesystem::exists(jsonOf(runs_dir, run), ec);
      if (written && (e.code == 0 || stopping)) {
        results[i].state = RunState::kRendered;
      } else if (stopping) {
        results[i].state = RunState::kInterrupted;
        cleanUpAfter(runs_dir, run, pid, true);
        continue;
      } else {
        results[i] = {RunState::kFailed, e.code == 0 ? "render exited without writing its outputs" : errorOf(e), {}};
        cleanUpAfter(runs_dir, run, pid, true);
        ++failed;
        if (tty) std::fputs("\r\033[K", stderr);
        std::cerr << "lodline: sweep: run " << run.name << " failed: " << results[i].error << '\n';
      }
      ++finished;
      if (tty) drawProgress(finished, pending.size(), failed, wall.elapsed());
    }
  }
  if (tty && !pending.empty()) std::fputc('\n', stderr);
  return !stopping;
}

int runSweep(const SweepOptions& o) {
  Stopwatch wall;
  auto plan_r = makePlan(o.plan);
  if (!plan_r) return reportError(plan_r.error());
  const Plan& plan = *plan_r;
  if (o.jobs < 1 || o.jobs > 64) return reportError(Error::usage("--jobs: must be 1..64"));
  if (o.output.empty()) return reportError(Error::usage("sweep: -o DIR is required"));
  if (static_cast<int>(o.dry_run) + static_cast<int>(o.emit_commands) + static_cast<int>(o.collect) > 1)
    return reportError(Error::usage("sweep: --dry-run, --emit-commands and --collect exclude each other"));
  if (o.collect && o.force) return reportError(Error::usage("sweep: --collect renders nothing, so --force does not apply"));
  if (o.sheet.columns < 0 || o.sheet.columns > 64)
    return reportError(Error::usage("--columns: must be 1..64 (0: automatic)"));
  if (o.sheet.cell_width < 0 || o.sheet.cell_width > 4096)
    return reportError(Error::usage("--cell-width: must be 0..4096 px"));
  std::string stat_names;
  for (const auto& c : statColumnNames()) stat_names += (stat_names.empty() ? "" : ", ") + c;
  for (const auto& c : o.charts)
    if (!isStatColumn(c)) return reportError(Error::usage("--chart " + c + ": not a result column (one of " + stat_names + ")"));
  for (const auto& c : o.sheet.captions)
    if (c != "run" && !isStatColumn(c) &&
        std::none_of(plan.axes.begin(), plan.axes.end(), [&](const Axis& a) { return a.key == c; }))
      return reportError(Error::usage("--caption " + c + ": not a result column (run, a varied key, or one of " +
                                      stat_names + ")"));
  // Every model is read once up front, as each run will read it: a broken file is one error
  // before anything is written, not one failed run per grid cell in a half-made directory.
  std::set<std::string> models;
  for (const auto& run : plan.runs) models.insert(run.model);
  for (const auto& model : models) {
    auto scene = loadScene(model);
    if (!scene) return reportError(scene.error());
    for (const SceneObject& object : scene->objects)
      if (auto mesh = loadObjectMesh(object); !mesh) return reportError(mesh.error());
  }
  std::error_code ec;
  auto font = Font::load(o.font);
  if (!font) return reportError(Error::runtime(font.error().message + " (install Debian's fonts-dejavu-core, or pass --font FILE.ttf)"));

  const std::filesystem::path dir(o.output), runs_dir = dir / "runs";
  std::vector<RunResult> results(plan.runs.size());
  for (size_t i = 0; i < plan.runs.size(); ++i)
    if (!o.force && std::filesystem::exists(pngOf(runs_dir, plan.runs[i]), ec) &&
        std::filesystem::exists(jsonOf(runs_dir, plan.runs[i]), ec))
      results[i].state = RunState::kComplete;
  const size_t complete = static_cast<size_t>(std::count_if(results.begin(), results.end(), [](const RunResult& r) {
    return r.state == RunState::kComplete;
  }));

  if (o.dry_run) {
    for (size_t i = 0; i < plan.runs.size(); ++i) {
      std::cout << plan.runs[i].name << "  " << (results[i].state == RunState::kComplete ? "done" : "pending")
                << "  lodline render " << shellQuote(plan.runs[i].model);
      for (const auto& a : plan.runs[i].args) std::cout << ' ' << shellQuote(a);
      std::cout << '\n';
    }
    std::cout << "sweep: " << plan.runs.size() << " runs: " << plan.runs.size() - complete << " to render, "
              << complete << " complete\n";
    return 0;
  }

  // The directory and its manifest: a rerun must be the same sweep (same model and fixed
  // options) unless --force, or its completed runs would not match their names.
  std::filesystem::create_directories(runs_dir, ec);
  if (ec || !std::filesystem::is_directory(runs_dir))
    return reportError(Error::runtime(o.output + ": cannot create directory: " + (ec ? ec.message() : "not a directory")));
  nlohmann::json manifest = {{"model", plan.model}, {"fixed", plan.fixed_given}};
  const auto manifest_path = dir / "sweep.json";
  if (std::ifstream in(manifest_path); in && !o.force) {
    const nlohmann::json old = nlohmann::json::parse(in, nullptr, false);
    const auto* old_model = old.is_object() && old.contains("model") ? old["model"].get_ptr<const std::string*>() : nullptr;
    const bool old_fixed_ok = old.is_object() && old.contains("fixed") && old["fixed"].is_array() &&
                              std::all_of(old["fixed"].begin(), old["fixed"].end(), [](const auto& t) { return t.is_string(); });
    if (!old_model || !old_fixed_ok)
      return reportError(Error::usage(manifest_path.string() + ": not a sweep manifest; choose another -o, or --force"));
    if (*old_model != plan.model || old["fixed"] != manifest["fixed"]) {
      std::string was;
      for (const auto& t : old["fixed"]) was += " " + t.get<std::string>();
      return reportError(Error::usage(manifest_path.string() + ": this directory holds a sweep of " +
                                      (old_model->empty() ? std::string("varied models") : *old_model) +
                                      " with fixed options [" + (was.empty() ? "" : was.substr(1)) +
                                      "]; use the same, choose another -o, or --force"));
    }
  }
  nlohmann::json axes_json = nlohmann::json::array();
  for (const auto& a : plan.axes) axes_json.push_back({{"key", a.key}, {"values", a.values}});
  manifest["axes"] = axes_json;
  manifest["zip"] = plan.zip;
  if (Status s = writeFileAtomically(manifest_path, [&](std::ostream& out) -> Status {
        out << manifest.dump(2) << '\n';
        return {};
      });
      !s)
    return reportError(s.error());

  char exe[4096];
  const ssize_t len = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (len <= 0) return reportError(Error::runtime("/proc/self/exe: cannot find the lodline executable"));
  exe[len] = 0;

  if (o.emit_commands) {
    // One line per pending run, runnable from any directory on a machine that sees the same
    // files: it changes to this directory (relative paths in the options stay valid) and
    // writes the run's PNG and JSON atomically, so a run cut short leaves nothing `--collect`
    // would take for done.
    const std::string cwd = std::filesystem::current_path(ec).string();
    for (size_t i = 0; i < plan.runs.size(); ++i) {
      if (results[i].state == RunState::kComplete) continue;
      const Run& run = plan.runs[i];
      std::cout << "cd " << shellQuote(cwd) << " && " << shellQuote(exe) << " render " << shellQuote(run.model);
      for (const auto& a : run.args) std::cout << ' ' << shellQuote(a);
      std::cout << " -o " << shellQuote(pngOf(runs_dir, run).string()) << " --stats "
                << shellQuote(jsonOf(runs_dir, run).string()) << '\n';
    }
    return 0;
  }

  // Ctrl-C from here on stops the renders; the summaries are still written (and are not
  // themselves cut short).
  std::signal(SIGINT, onSweepInterrupt);
  std::signal(SIGTERM, onSweepInterrupt);
  const bool finished = o.collect || executeRuns(exe, plan.runs, runs_dir, o.jobs, results);

  // Stats of every run with outputs (rendered now or kept from before).
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    if (!hasStats(results[i])) continue;
    std::ifstream in(jsonOf(runs_dir, plan.runs[i]));
    results[i].stats = nlohmann::json::parse(in, nullptr, false);
    if (results[i].stats.is_discarded())
      results[i] = {RunState::kFailed, jsonOf(runs_dir, plan.runs[i]).string() + ": unreadable stats JSON (rerun with --force)", {}};
  }
  std::vector<std::filesystem::path> written;
  Status failure;
  if (Status s = writeResultsCsv(dir / "results.csv", plan, results); !s) failure = s;
  else written.push_back(dir / "results.csv");
  if (failure) {
    auto sheets = writeSheets(plan, results, dir, runs_dir, *font, o.sheet);
    if (!sheets) failure = sheets.error();
    else written.insert(written.end(), sheets->begin(), sheets->end());
  }
  if (failure) {
    auto charts = writeCharts(plan, results, dir, o.charts);
    if (!charts) failure = charts.error();
    else written.insert(written.end(), charts->begin(), charts->end());
  }

  size_t rendered = 0, failed = 0, not_run = 0;
  for (const auto& r : results) {
    rendered += r.state == RunState::kRendered;
    failed += r.state == RunState::kFailed;
    not_run += r.state == RunState::kPending || r.state == RunState::kInterrupted;
  }
  char secs[32];
  std::snprintf(secs, sizeof(secs), "%.1f", wall.elapsed() / 1000.0);
  std::cout << "sweep: " << plan.runs.size() << " runs: " << rendered << " rendered, " << complete
            << " skipped (complete from before), " << failed << " failed";
  if (not_run) std::cout << ", " << not_run << " not run";
  std::cout << " (" << secs << " s)\n";
  for (const auto& f : written) std::cout << "  " << f.string() << '\n';
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!failure) return reportError(failure.error());
  if (!finished) {
    std::cerr << "lodline: sweep interrupted; " << not_run << " run(s) not done (rerun the same command to finish)\n";
    return 130;
  }
  if (o.collect && not_run) {
    std::cerr << "lodline: sweep --collect: " << not_run << " run(s) have no PNG and JSON in " << runs_dir.string()
              << " yet (render them, e.g. with --emit-commands)\n";
    return 1;
  }
  return failed ? 1 : 0;
}

}  // namespace

Command addSweepCommand(CLI::App& parent) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "sweep", "Render a parameter sweep (cross product of --vary lists) into PNGs, stats, results.csv, "
               "contact sheets and charts");
  cmd->add_option("model", o->plan.model,
                  "Mesh or scene file, passed to every `lodline render` unchanged (or --vary model=A,B,...)");
  cmd->add_option("render-options", o->plan.passthrough,
                  "Render options for every run, after `--` (e.g. -- --style lines --size 480x270)");
  cmd->add_option("-o,--output", o->output,
                  "Sweep directory: runs/NAME.png and .json per run, results.csv, sheet*.png, chart_*.svg");
  cmd->add_option("--vary", o->plan.vary,
                  "KEY=V1,V2,...: a render option without its dashes (target-area, detail-map, lod, size, ...) "
                  "or view.az, view.el, view.dist (one part of --view AZ,EL,DIST), or model (files, instead of "
                  "MODEL); an empty value passes no option (render's default); values are split at ';' "
                  "instead of ',' when the list holds a ';' (view=0,20,3;90,20,3). Repeatable: runs are the "
                  "cross product, first axis slowest")
      ->allow_extra_args(false);
  cmd->add_flag("--zip", o->plan.zip, "Pair the --vary lists (equal lengths) instead of crossing them");
  cmd->add_option("--set", o->plan.set, "KEY=VALUE: a render option fixed for every run (repeatable; like -- --KEY VALUE)")
      ->allow_extra_args(false);
  cmd->add_option("-j,--jobs", o->jobs, "Runs rendered at the same time (child processes)")->capture_default_str();
  cmd->add_flag("--force", o->force, "Render every run again, even those whose PNG and JSON exist");
  cmd->add_flag("--dry-run", o->dry_run, "Check everything and print each run's name, state and render command; render nothing");
  cmd->add_flag("--emit-commands", o->emit_commands,
                "Render nothing: print one self-contained shell command per pending run (for GNU parallel, a Slurm "
                "job array or any scheduler); then --collect gathers the results");
  cmd->add_flag("--collect", o->collect,
                "Render nothing: build results.csv, the contact sheets and the charts from the runs already in the "
                "directory (rendered elsewhere); exit 1 when some runs are missing");
  cmd->add_option("--chart", o->charts,
                  "Result column to plot against the first --vary axis, one line per value of the others "
                  "(repeatable; DIR/chart_COLUMN.svg)")
      ->allow_extra_args(false);
  cmd->add_option("--caption", o->sheet.captions, "Result column to print under each contact-sheet cell (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--cell-width", o->sheet.cell_width, "Contact-sheet cell width in px (default: the render width, at most 320)");
  cmd->add_option("--columns", o->sheet.columns,
                  "Cells per row of a --zip contact sheet (default: one row up to 5 runs, else a square)");
  cmd->add_option("--title", o->sheet.title, "Contact-sheet title (default: the model and the axes)");
  cmd->add_option("--font", o->font, "TrueType font of the contact-sheet labels")->capture_default_str();
  // Every drawing option of `render`, fixed for every run (the same as after `--`).
  const size_t own = cmd->get_options().size();
  addViewOptions(*cmd, o->render_view);
  addDetailOptions(*cmd, o->render_detail);
  const std::vector<CLI::Option*> all = cmd->get_options([](CLI::Option*) { return true; });
  for (size_t i = own; i < all.size(); ++i) {
    CLI::Option* opt = all[i];
    if (opt->get_positional()) {  // render's model: the sweep has its own
      cmd->remove_option(opt);
      continue;
    }
    o->render_options.push_back(opt);
    opt->group("Render options (fixed for every run)");
  }
  cmd->footer(
      "Each run is `lodline render MODEL [fixed options] --KEY=VALUE ... -o DIR/runs/NAME.png --stats "
      "DIR/runs/NAME.json`, NAME made of the varied values (target-area-4_view.dist-2.5). All option keys and "
      "values are checked before anything renders. A run whose PNG and JSON exist is kept (skipped) unless "
      "--force; failed runs are reported, recorded in results.csv and rendered again next time. Contact sheets: "
      "rows = first --vary axis, columns = second, one sheet per value of further axes (sheet_KEY-VALUE.png); "
      "one axis or --zip: one sheet, cells captioned. Ctrl-C stops the running renders and writes the summaries "
      "of the runs done. Exit status: 0 all runs done, 1 some failed, 2 usage error, 130 interrupted. "
      "See docs/experiments.md.");
  return {cmd, [o] {
            const auto given = givenRenderOptions(o->render_options);
            o->plan.passthrough.insert(o->plan.passthrough.begin(), given.begin(), given.end());
            return runSweep(*o);
          }};
}

}  // namespace lodline
