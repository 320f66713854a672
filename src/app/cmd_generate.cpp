// `lodline generate SHAPE -o FILE`: writes one of the project's analytic surfaces (the
// default model in models/ was made this way), or one of the stroke styles' brushes as a PNG
// (models/brushes/ was made this way; docs/strokes.md).
#include <algorithm>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "io/generate.h"
#include "io/image.h"
#include "io/stroke_style_file.h"
#include "io/load_mesh.h"

namespace lodline {

Command addGenerateCommand(CLI::App& parent) {
  struct Opts {
    std::string shape;
    std::string output;
    int resolution = 0;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = parent.add_subcommand(
      "generate",
      "Write an analytic test surface as an OFF file (knot = the default model), or a stroke brush as a PNG");
  cmd->add_option("shape", o->shape,
                  "sphere, uvsphere, torus, cylinder, ellipsoid, grid, terrain or knot; brush-pencil or brush-marker")
      ->required()
      ->check(CLI::IsMember({"sphere", "uvsphere", "torus", "cylinder", "ellipsoid", "grid", "terrain", "knot",
                             "brush-pencil", "brush-marker"}));
  cmd->add_option("-o,--output", o->output, "Output .off file (.png for a brush)")->required();
  cmd->add_option("--resolution", o->resolution,
                  "Subdivision level (sphere, ellipsoid) or segments (others); 0 = a sensible default");
  return {cmd, [o]() -> int {
            if (o->shape.starts_with("brush-")) {
              const Image brush = makeBrush(o->shape == "brush-pencil" ? BrushKind::kPencil : BrushKind::kMarker);
              if (Status s = writePng(o->output, brush); !s) return reportError(s.error());
              std::cout << "wrote " << o->output << ": " << brush.width << "x" << brush.height << " brush\n";
              return 0;
            }
            const int r = o->resolution;
            const bool levels = o->shape == "sphere" || o->shape == "ellipsoid";
            if (r < 0 || (levels && r > 9) || (!levels && r > 16384))
              return reportError(Error::usage("--resolution: " + std::to_string(r) + " is out of range for " +
                                              o->shape + (levels ? " (0-9)" : " (0-16384)")));
            TriMesh m;
            if (o->shape == "sphere") m = makeIcoSphere(1.0f, r > 0 ? r : 4);
            else if (o->shape == "uvsphere") m = makeUvSphere(1.0f, r > 0 ? r : 64, r > 0 ? r / 2 : 32);
            else if (o->shape == "torus") m = makeTorus(1.0f, 0.35f, r > 0 ? r : 96, r > 0 ? r / 2 : 48);
            else if (o->shape == "cylinder") m = makeCylinder(0.5f, 2.0f, r > 0 ? r : 64, r > 0 ? r : 32);
            else if (o->shape == "ellipsoid") m = makeEllipsoid(1.0f, 0.6f, 0.4f, r > 0 ? r : 4);
            else if (o->shape == "grid") m = makeGrid(2.0f, r > 0 ? r : 64);
            else if (o->shape == "terrain") m = makeTerrain(2.0f, r > 0 ? r : 256);
            else m = makeTorusKnot(2, 3, 1.0f, 0.16f, r > 0 ? r : 720, r > 0 ? std::max(8, r / 15) : 48, 0.18f);
            if (Status s = saveOff(o->output, m); !s) return reportError(s.error());
            std::cout << "wrote " << o->output << ": " << m.vertexCount() << " vertices, "
                      << m.faceCount() << " faces\n";
            return 0;
          }};
}

}  // namespace lodline
