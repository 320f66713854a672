// The kinds of line lodline draws: one enum for the lines stage (extraction, strokes), the
// styles, the renderers and the outputs. Values index per-kind arrays and follow the
// drawing order.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace lodline {

enum class LineKind : uint8_t {
  kContour = 0,     ///< occluding contours, n·v = 0
  kSuggestive = 1,  ///< suggestive contours, kr = 0 where Dw kr > 0
  kCrease = 2,      ///< edges with a large dihedral angle (and marked edges)
  kBoundary = 3,    ///< edges with one face
  /// where two objects' surfaces (or two parts of one surface) cross (cgal/intersections.h)
  kIntersection = 4,
  /// level sets of the shading n·l at multiples of a spacing (l: the frame's light)
  kIsophote = 5,
  /// level sets of the height along an up axis at multiples of a spacing
  kTopo = 6,
  /// parabolic lines, K = k1·k2 = 0, where the surface is curved at all
  kParabolic = 7,
  /// ridges: maxima of the dominant positive curvature along its line of curvature
  kRidge = 8,
  /// valleys: the same for the dominant negative curvature
  kValley = 9,
  /// suggestive highlights, kr = 0 where Dw kr < 0 (DeCarlo & Rusinkiewicz 2007)
  kSuggestiveHighlight = 10,
  /// apparent ridges, maxima of the view-dependent curvature (Judd et al. 2007)
  kApparentRidge = 11,
  /// principal highlights, maxima of n·v across the dominant curvature (DeCarlo &
  /// Rusinkiewicz 2007)
  kPrincipalHighlight = 12,
  /// edges between faces of different materials (TriMesh::face_materials)
  kMaterial = 13,
};
inline constexpr int kLineKindCount = 14;

/// "contour", "suggestive", "crease", "boundary", "intersection", "isophote", "topo",
/// "parabolic", "ridge", "valley", "suggestive-highlight", "apparent-ridge",
/// "principal-highlight", "material" (the names of --lines and the stats).
const char* lineKindName(LineKind k);
/// The kind named `name`, if any.
std::optional<LineKind> parseLineKind(std::string_view name);
/// Every kind's name, comma-separated ("contour, suggestive, ...") for messages.
const char* lineKindList();

}  // namespace lodline
