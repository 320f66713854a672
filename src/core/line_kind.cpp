#include "core/line_kind.h"

namespace lodline {

const char* lineKindName(LineKind k) {
  switch (k) {
    case LineKind::kContour: return "contour";
    case LineKind::kSuggestive: return "suggestive";
    case LineKind::kCrease: return "crease";
    case LineKind::kBoundary: return "boundary";
    case LineKind::kIntersection: return "intersection";
    case LineKind::kIsophote: return "isophote";
    case LineKind::kTopo: return "topo";
    case LineKind::kParabolic: return "parabolic";
    case LineKind::kRidge: return "ridge";
    case LineKind::kValley: return "valley";
    case LineKind::kSuggestiveHighlight: return "suggestive-highlight";
    case LineKind::kApparentRidge: return "apparent-ridge";
    case LineKind::kPrincipalHighlight: return "principal-highlight";
    case LineKind::kMaterial: return "material";
  }
  return "unknown";
}

std::optional<LineKind> parseLineKind(std::string_view name) {
  for (int k = 0; k < kLineKindCount; ++k)
    if (name == lineKindName(static_cast<LineKind>(k))) return static_cast<LineKind>(k);
  return std::nullopt;
}

const char* lineKindList() {
  return "contour, suggestive, crease, boundary, intersection, isophote, topo, parabolic, ridge, valley, "
         "suggestive-highlight, apparent-ridge, principal-highlight, "
         "material";
}

}  // namespace lodline
