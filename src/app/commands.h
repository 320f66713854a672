// The subcommands of the `lodline` program. Each run returns the process exit code:
// 0 success, 1 runtime error (bad file, no context, failed write), 2 usage error.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "core/mesh.h"
#include "core/result.h"

namespace lodline {

struct Command {
  CLI::App* app = nullptr;    ///< the subcommand, owned by the parent CLI::App
  std::function<int()> run;   ///< runs it after parsing
};

Command addRenderCommand(CLI::App& parent);
Command addViewCommand(CLI::App& parent);
Command addGenerateCommand(CLI::App& parent);
Command addCaptureCommand(CLI::App& parent);
Command addBuildCommand(CLI::App& parent);
Command addSimplifyCommand(CLI::App& parent);
Command addCompareCommand(CLI::App& parent);
Command addBenchCommand(CLI::App& parent);
Command addSweepCommand(CLI::App& parent);

/// Parses an error bound given as a percentage of the bounding-box diagonal ("0.02%" or
/// "0.02") into a fraction (0.0002); usage error naming `option` otherwise.
Result<double> parsePercent(const std::string& text, const std::string& option);

/// Outcome of simplifyMesh().
struct SimplifyOutcome {
  TriMesh mesh;            ///< the simplified mesh
  double e_s_rel = 0.0;    ///< measured E_s / diagonal
  double e_s = 0.0;        ///< measured E_s, model units
  double hausdorff = 0.0;  ///< symmetric Hausdorff distance over the vertices, model units
  int evaluations = 0;     ///< E_s measurements made by the search
};

/// Static pre-simplification of Pan, Zhou, Shi (DESIGN.md §4): the quadric-error collapses of
/// the progressive-mesh builder, stopped where the measured E_s (CGAL AABB tree) would exceed
/// `bound` × the bounding-box diagonal. `what` names the model in errors. Needs lodline_cgal.
Result<SimplifyOutcome> simplifyMesh(const TriMesh& mesh, double bound, const std::string& what);

/// Prints "lodline: <message>" to stderr and returns the error's exit code.
int reportError(const Error& e);

}  // namespace lodline
