// lodline: line drawings of 3D meshes at a chosen scale in the image.
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "lodline: renders 3D triangle meshes as line drawings (silhouettes, suggestive contours,\n"
      "creases) over toon shading, headless (EGL/OSMesa) or in a window.\n"
      "Run `lodline COMMAND --help` for the options of each command.",
      "lodline"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "lodline 0.1.0");
  const std::vector<lodline::Command> commands = {
      lodline::addRenderCommand(app), lodline::addViewCommand(app), lodline::addCaptureCommand(app),
      lodline::addBuildCommand(app), lodline::addGenerateCommand(app),
      lodline::addSimplifyCommand(app), lodline::addCompareCommand(app), lodline::addBenchCommand(app),
      lodline::addSweepCommand(app), lodline::addJoinCommand(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "lodline: " << e.what() << " (run `lodline --help` for usage)\n";  // one line
    return 2;
  }
  for (const auto& c : commands)
    if (c.app->parsed()) return c.run();
  return 2;
}
