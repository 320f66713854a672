// `lodline simplify MODEL --max-error E% -o OUT.off`: error-bounded static simplification
// (cgal/simplify.h: Pan, Zhou, Shi's static half, docs/design.md §2.4).
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "core/timer.h"
#include "io/load_mesh.h"
#include "cgal/simplify.h"

namespace lodline {

Result<double> parsePercent(const std::string& text, const std::string& option) {
  std::string t = text;
  if (!t.empty() && t.back() == '%') t.pop_back();
  char* end = nullptr;
  const double v = t.empty() ? -1.0 : std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !(v >= 0.0 && v <= 100.0))
    return Error::usage(option + ": expected a percentage of the bounding-box diagonal in [0, 100], e.g. 0.02%, got '" +
                        text + "'");
  return v / 100.0;
}

Command addSimplifyCommand(CLI::App& parent) {
  struct Opts {
    std::string model, output, max_error = "0.02%";
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = parent.add_subcommand(
      "simplify",
      "Simplify a mesh within an approximation error E_s (Pan/Zhou/Shi) relative to its bounding-box diagonal");
  cmd->add_option("model", o->model, "Mesh file (.off, .obj, .ply, .stl)")->required();
  cmd->add_option("--max-error", o->max_error,
                  "Largest E_s as a percentage of the bounding-box diagonal (0.02% is the paper's 'invisible')")
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Output mesh (.off, written atomically)")->required();
  return {cmd, [o]() -> int {
            auto bound = parsePercent(o->max_error, "--max-error");
            if (!bound) return reportError(bound.error());
            Stopwatch sw;
            auto mesh = loadMesh(o->model);
            if (!mesh) return reportError(mesh.error());
            auto s = simplifyMesh(*mesh, *bound, o->model);
            if (!s) return reportError(s.error());
            if (Status st = saveOff(o->output, s->mesh); !st) return reportError(st.error());
            std::cout << std::setprecision(4) << "wrote " << o->output << ": " << mesh->faceCount() << " -> "
                      << s->mesh.faceCount() << " faces, " << mesh->vertexCount() << " -> " << s->mesh.vertexCount()
                      << " vertices; E_s " << s->e_s << " (" << 100.0 * s->e_s_rel << "% of the diagonal, bound "
                      << 100.0 * *bound << "%), Hausdorff " << s->hausdorff << "; " << s->evaluations
                      << " E_s evaluations, " << std::setprecision(3) << sw.elapsed() / 1000.0 << " s\n";
            return 0;
          }};
}

}  // namespace lodline
