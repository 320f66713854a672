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
Command addJoinCommand(CLI::App& parent);

/// Parses an error bound given as a percentage of the bounding-box diagonal ("0.02%" or
/// "0.02") into a fraction (0.0002); usage error naming `option` otherwise.
Result<double> parsePercent(const std::string& text, const std::string& option);

/// Prints "lodline: <message>" to stderr and returns the error's exit code.
int reportError(const Error& e);

}  // namespace lodline
