// `lodline compare A B`: Pan, Zhou, Shi's approximation error E_s of mesh B against mesh A
// (docs/design.md §2.4; exact point-to-triangle distances through CGAL's AABB tree, src/cgal),
// absolute and relative to A's bounding-box diagonal, and the symmetric Hausdorff distance
// over the vertices of both meshes.
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "io/load_mesh.h"
#ifdef LODLINE_HAVE_CGAL
#include "cgal/mesh_distance.h"
#endif

namespace lodline {

Command addCompareCommand(CLI::App& parent) {
  struct Opts {
    std::string a, b;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = parent.add_subcommand(
      "compare", "Approximation error E_s (Pan/Zhou/Shi) and Hausdorff distance between two meshes");
  cmd->add_option("original", o->a, "Original mesh M_o (its bounding-box diagonal is the scale)")->required();
  cmd->add_option("simplified", o->b, "Simplified (or any other) mesh M_s")->required();
  return {cmd, [o]() -> int {
            auto a = loadMesh(o->a);
            if (!a) return reportError(a.error());
            auto b = loadMesh(o->b);
            if (!b) return reportError(b.error());
#ifdef LODLINE_HAVE_CGAL
            auto ta = SurfaceDistance::create(*a, o->a);
            if (!ta) return reportError(ta.error());
            if (auto tb = SurfaceDistance::create(*b, o->b); !tb) return reportError(tb.error());
            auto d = measureMeshDistance(*a, *ta, *b);
            if (!d) return reportError(Error::runtime(o->b + ": " + d.error().message));
            std::cout << std::setprecision(6) << o->a << ": " << a->faceCount() << " faces, " << a->vertexCount()
                      << " vertices; " << o->b << ": " << b->faceCount() << " faces, " << b->vertexCount()
                      << " vertices\n"
                      << "bounding-box diagonal " << d->diagonal << "\n"
                      << "E_s " << d->e_s << " (" << 100.0 * d->relativeEs() << "% of the diagonal)\n"
                      << "mean d(X_o, M_s) " << d->mean_o_to_s << ", mean d(X_s, M_o) " << d->mean_s_to_o << "\n"
                      << "Hausdorff " << d->hausdorff << " (" << 100.0 * d->relativeHausdorff()
                      << "% of the diagonal)\n";
            return 0;
#else
            return reportError(Error::runtime("lodline was built without CGAL (libcgal-dev): compare is unavailable"));
#endif
          }};
}

}  // namespace lodline
