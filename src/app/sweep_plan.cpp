// `lodline sweep`: the runs of a sweep and the check of their render options (sweep.h).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/model.h"
#include "app/options.h"
#include "app/sweep.h"
#include "core/hash.h"
#include "gl/context.h"

namespace lodline::sweep {
namespace {

constexpr const char* kViewKeys[] = {"view.az", "view.el", "view.dist"};

int viewComponent(const std::string& key) {
  for (int i = 0; i < 3; ++i)
    if (key == kViewKeys[i]) return i;
  return -1;
}

// Options the sweep sets itself for every run.
bool ownedKey(const std::string& key) {
  return key == "output" || key == "o" || key == "stats" || key == "svg" || key == "help";
}

// Shortest text that reads back as `v` ("2.5", "35", "-10").
std::string formatFloat(float v) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return ec == std::errc() ? std::string(buf, p) : std::to_string(v);
}

std::vector<std::string> splitList(const std::string& s) {
  const char sep = s.find(';') != std::string::npos ? ';' : ',';
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t end = s.find(sep, start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

std::string runName(const std::vector<Axis>& axes, const std::vector<size_t>& index) {
  std::string name;
  for (size_t a = 0; a < axes.size(); ++a) {
    if (a) name += '_';
    name += namePart(axes[a].key, axes[a].values[index[a]]);
  }
  if (name.size() > 200) {  // file names are limited to 255 bytes
    char hash[16];
    std::snprintf(hash, sizeof(hash), "%08x", static_cast<uint32_t>(hashText(name)));
    name = name.substr(0, 190) + "-" + hash;
  }
  return name;
}

// The option name of a command-line token: "--size=1x1" and "--size" give "size", "-o" gives "o".
std::string tokenKey(const std::string& token) {
  if (token.rfind("--", 0) == 0) return token.substr(2, token.find('=') == std::string::npos ? std::string::npos : token.find('=') - 2);
  if (token.size() == 2 && token[0] == '-' && token[1] != '-') return token.substr(1);
  return {};
}

// ---- Checking render options without rendering -------------------------------------------

// Syntax and option names, by the render command's own parser (so any option render gains is
// accepted here too).
Status checkRenderSyntax(const std::string& model, const std::vector<std::string>& args) {
  CLI::App root{"lodline", "lodline"};
  const Command render = addRenderCommand(root);
  std::vector<std::string> argv = {"render", model};
  argv.insert(argv.end(), args.begin(), args.end());
  for (const char* extra : {"-o", "sweep-check.png", "--stats", "sweep-check.json"}) argv.push_back(extra);
  std::reverse(argv.begin(), argv.end());
  try {
    root.parse(argv);
  } catch (const CLI::ParseError& e) {
    return Error::usage(e.what());
  }
  return {};
}

struct CheckedArgs {
  ResolvedView view;
  std::filesystem::path cache_dir;
};

// Values, by the functions render resolves its options with (reads detail maps).
Result<CheckedArgs> checkRenderValues(const std::string& model, const std::vector<std::string>& args) {
  CLI::App app{"check", "check"};
  app.allow_extras();
  ViewOptions view;
  DetailOptions detail;
  std::string context = "auto", backend = "gl";
  addViewOptions(app, view);
  addDetailOptions(app, detail);
  app.add_option("--context", context);
  app.add_option("--backend", backend);
  std::vector<std::string> argv = {model};
  argv.insert(argv.end(), args.begin(), args.end());
  std::reverse(argv.begin(), argv.end());
  try {
    app.parse(argv);
  } catch (const CLI::ParseError& e) {
    return Error::usage(e.what());
  }
  // Values of render-only options (e.g. --max-adapt-frames 5) land among the positionals
  // here; checkRenderSyntax has checked that there is one model.
  view.models = {model};
  auto resolved = resolveViewOptions(view);
  if (!resolved) return resolved.error();
  auto d = resolveDetailOptions(detail);
  if (!d) return d.error();
  if (auto b = parseContextBackend(context); !b) return b.error();
  if (backend != "gl" && backend != "soft")  // as render checks it
    return Error::usage("--backend: expected gl or soft, got '" + backend + "'");
  const auto* pm = std::get_if<ProgressiveDetail>(&d->lod);
  return CheckedArgs{*resolved, pm ? pm->cache_dir : std::filesystem::path()};
}

// ---- The plan ----------------------------------------------------------------------------

Result<Axis> parseVary(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    return Error::usage("--vary: expected KEY=V1,V2,... (e.g. target-area=4,8,16), got '" + spec + "'");
  Axis axis{spec.substr(0, eq), splitList(spec.substr(eq + 1))};
  return axis;
}

Status checkKey(const std::string& key, const std::string& flag, const CLI::App& render) {
  if (viewComponent(key) >= 0 || (key == "model" && flag == "--vary")) return {};
  if (ownedKey(key))
    return Error::usage(flag + " " + key + ": sweep sets -o, --stats and --svg of each run itself (DIR/runs/NAME.png, .json)");
  if (!render.get_option_no_throw("--" + key))
    return Error::usage(flag + " " + key + ": `lodline render` has no option --" + key +
                        " (keys are render options without the dashes, view.az, view.el, view.dist or model)");
  return {};
}

}  // namespace

Result<Plan> makePlan(const PlanOptions& o) {
  Plan plan;
  plan.model = o.model;
  plan.zip = o.zip;
  CLI::App root{"lodline", "lodline"};
  const Command render = addRenderCommand(root);
  if (o.vary.empty()) return Error::usage("sweep: give at least one --vary KEY=V1,V2,...");
  std::set<std::string> keys;
  for (const auto& spec : o.vary) {
    auto axis = parseVary(spec);
    if (!axis) return axis.error();
    if (Status s = checkKey(axis->key, "--vary", *render.app); !s) return s.error();
    if (!keys.insert(axis->key).second) return Error::usage("--vary " + axis->key + ": given twice");
    if (!o.zip) {
      std::set<std::string> seen;
      for (const auto& v : axis->values)
        if (!seen.insert(v).second) return Error::usage("--vary " + axis->key + ": value '" + v + "' given twice");
    }
    plan.axes.push_back(std::move(axis.value()));
  }
  if (keys.count("view") && (keys.count("view.az") || keys.count("view.el") || keys.count("view.dist")))
    return Error::usage("--vary view: vary either the whole --view or its components view.az/el/dist, not both");
  // The model: MODEL, or one per value of --vary model.
  if (keys.count("model") && !o.model.empty())
    return Error::usage("--vary model: give either MODEL or --vary model=A,B,..., not both");
  if (!keys.count("model") && o.model.empty()) return Error::usage("sweep: give a MODEL (or --vary model=A,B,...)");
  std::string check_model = o.model;  // a model to check the fixed options with
  for (const auto& a : plan.axes)
    if (a.key == "model") {
      for (const auto& v : a.values)
        if (v.empty()) return Error::usage("--vary model: empty model name");
      check_model = a.values[0];
    }

  // Fixed options: --set KEY=VALUE as --KEY=VALUE, then everything after --.
  std::array<std::optional<std::string>, 3> set_view;
  for (const auto& spec : o.set) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
      return Error::usage("--set: expected KEY=VALUE (e.g. style=lines), got '" + spec + "'");
    const std::string key = spec.substr(0, eq), value = spec.substr(eq + 1);
    if (Status s = checkKey(key, "--set", *render.app); !s) return s.error();
    if (keys.count(key)) return Error::usage("--set " + key + ": also varied by --vary " + key + "; fix it or vary it");
    if (const int c = viewComponent(key); c >= 0) set_view[c] = value;
    else plan.fixed.push_back("--" + key + "=" + value);
    plan.fixed_given.push_back("--" + key + "=" + value);
  }
  for (const auto& t : o.passthrough) {
    const std::string key = tokenKey(t);
    if (ownedKey(key))
      return Error::usage("after --: " + t + " is set by sweep for each run (DIR/runs/NAME.png, .json); sweep's "
                          "own options (-o DIR) go before --");
    if (!key.empty() && keys.count(key))
      return Error::usage("after --: " + t + " is also varied by --vary " + key + "; fix it or vary it");
    plan.fixed.push_back(t);
    plan.fixed_given.push_back(t);
  }

  // View components: the base --view (fixed options, else the default 3/4 view at the framing
  // distance) with --set and --vary components replacing its parts.
  const bool view_parts = std::any_of(set_view.begin(), set_view.end(), [](const auto& v) { return v.has_value(); }) ||
                          std::any_of(plan.axes.begin(), plan.axes.end(),
                                      [](const Axis& a) { return viewComponent(a.key) >= 0; });
  std::optional<std::string> base_view;
  if (view_parts) {
    std::vector<std::string> kept;
    for (size_t i = 0; i < plan.fixed.size(); ++i) {
      const std::string& t = plan.fixed[i];
      if (t == "--view" && i + 1 < plan.fixed.size()) {
        base_view = plan.fixed[++i];
      } else if (t.rfind("--view=", 0) == 0) {
        base_view = t.substr(7);
      } else {
        kept.push_back(t);
      }
    }
    plan.fixed = std::move(kept);
  }
  if (Status s = checkRenderSyntax(check_model, plan.fixed); !s)
    return Error::usage("sweep: fixed render options: " + s.error().message);
  if (auto c = checkRenderValues(check_model, plan.fixed); !c)
    return Error{c.error().kind, "sweep: fixed render options: " + c.error().message};

  // The runs: cross product (first axis slowest) or paired lists.
  std::vector<std::vector<size_t>> indices;
  if (o.zip) {
    for (const auto& a : plan.axes)
      if (a.values.size() != plan.axes[0].values.size())
        return Error::usage("--zip: every --vary list needs the same length (" + plan.axes[0].key + " has " +
                            std::to_string(plan.axes[0].values.size()) + " values, " + a.key + " has " +
                            std::to_string(a.values.size()) + ")");
    for (size_t i = 0; i < plan.axes[0].values.size(); ++i) indices.emplace_back(plan.axes.size(), i);
  } else {
    size_t total = 1;
    for (const auto& a : plan.axes) {
      total *= a.values.size();
      if (total > 100000) return Error::usage("sweep: more than 100000 runs; narrow the --vary lists");
    }
    for (size_t r = 0; r < total; ++r) {
      std::vector<size_t> idx(plan.axes.size());
      size_t rest = r;
      for (size_t a = plan.axes.size(); a-- > 0;) {
        idx[a] = rest % plan.axes[a].values.size();
        rest /= plan.axes[a].values.size();
      }
      indices.push_back(std::move(idx));
    }
  }

  // Each run's render options, checked as render would check them. An empty value passes no
  // option (render's default).
  auto makeRun = [&](const std::vector<std::pair<std::string, std::string>>& varied) -> Result<Run> {
    Run run;
    run.model = o.model;
    run.args = plan.fixed;
    std::optional<std::string> comps[3];
    for (const auto& [key, value] : varied)
      if (key == "model") run.model = value;
      else if (const int c = viewComponent(key); c >= 0) comps[c] = value;
      else if (!value.empty()) run.args.push_back("--" + key + "=" + value);  // empty: render's default
    if (view_parts) {
      OrbitView v;
      if (base_view) {
        auto parsed = parseOrbitView(*base_view);
        if (!parsed) return parsed.error();
        v = *parsed;
      }
      float* parts[3] = {&v.azimuth_deg, &v.elevation_deg, &v.distance};
      for (int c = 0; c < 3; ++c) {
        const auto& value = comps[c] ? comps[c] : set_view[c];
        if (!value) continue;
        const auto number = parseNumber(*value);
        if (!number) return Error::usage(std::string(kViewKeys[c]) + ": '" + *value + "' is not a number");
        *parts[c] = static_cast<float>(*number);
      }
      if (v.distance == 0.0f) {  // the distance that frames the model, as render's default view
        auto checked = checkRenderValues(run.model, run.args);
        if (!checked) return checked.error();
        Bounds unit;
        unit.radius = 1.0f;
        const Camera cam = orbitCamera(unit, v, checked->view.fov_deg, checked->view.frame.aspect());
        v.distance = glm::length(cam.eye - cam.target);
      }
      run.args.push_back("--view=" + formatFloat(v.azimuth_deg) + "," + formatFloat(v.elevation_deg) + "," +
                         formatFloat(v.distance));
    }
    if (Status s = checkRenderSyntax(run.model, run.args); !s) return s.error();
    auto checked = checkRenderValues(run.model, run.args);
    if (!checked) return checked.error();
    run.cache_dir = checked->cache_dir;
    return run;
  };
  std::set<std::string> names;
  for (const auto& idx : indices) {
    std::vector<std::pair<std::string, std::string>> varied;
    for (size_t a = 0; a < plan.axes.size(); ++a) varied.emplace_back(plan.axes[a].key, plan.axes[a].values[idx[a]]);
    const std::string name = runName(plan.axes, idx);
    auto run = makeRun(varied);
    if (!run) {
      // Name the value when it is bad on its own; otherwise the combination is (e.g.
      // t-collapse with t-split).
      for (const auto& [key, value] : varied)
        if (auto alone = makeRun({{key, value}}); !alone)
          return Error{alone.error().kind, "--vary " + key + "=" + value +
                                               (varied.size() > 1 ? " (run " + name + ")" : std::string()) + ": " +
                                               alone.error().message};
      return Error{run.error().kind, "sweep: run " + name + ": " + run.error().message};
    }
    run->name = name;
    run->index = idx;
    if (!names.insert(name).second) return Error::usage("--zip: run " + name + " appears twice (same values)");
    plan.runs.push_back(std::move(run.value()));
  }
  return plan;
}

// Paths, commas and spaces become '-' (a path keeps its file stem), and the hash keeps the
// name unique: "detail-map-split-1a2b3c4d".
std::string namePart(const std::string& key, const std::string& value) {
  auto safe = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-'; };
  if (std::all_of(value.begin(), value.end(), safe)) return key + "-" + value;
  std::string shown = value;
  if (value.find('/') != std::string::npos) shown = std::filesystem::path(value).stem().string();
  for (char& c : shown)
    if (!safe(c)) c = '-';
  if (shown.size() > 40) shown.resize(40);
  char hash[16];
  std::snprintf(hash, sizeof(hash), "%08x", static_cast<uint32_t>(hashText(value)));
  return key + "-" + shown + (shown.empty() ? "" : "-") + hash;
}

std::optional<double> parseNumber(const std::string& s) {
  double v = 0.0;
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (b != e && *b == '+') ++b;
  auto [p, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || p != e || b == e || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace lodline::sweep
