// Line extraction: every view-dependent line is the zero set of a per-vertex scalar, masked
// by the sign of a per-vertex test num/den, found by one generic extractor (docs/design.md
// §3.6); creases and boundaries come from the edge list.
//
// Papers: DeCarlo, Finkelstein, Rusinkiewicz, Santella, "Suggestive Contours for Conveying
// Shape" (SIGGRAPH 2003), §4 (object-space extraction on faces, threshold on the derivative);
// DeCarlo, Finkelstein, Rusinkiewicz, "Interactive Rendering of Suggestive Contours with
// Temporal Coherence" (NPAR 2004), §3–4 (tanθ·Dw kr test computed as num/den, fading of weak
// lines); Jeong et al. 2005 §4 (contours and suggestive contours on the adapted mesh).
//
// Exact chaining: an edge's zero crossing is always interpolated from the edge's first vertex
// to its second, so the two faces sharing an edge emit bit-identical endpoints with the same
// point id (the edge's index).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/line_kind.h"
#include "core/mesh.h"
#include "core/worker_pool.h"
#include "lines/view_quantities.h"
#include "shape/adjacency.h"
#include "shape/shape_cache.h"

namespace lodline {

/// LineParams::ridge_estimator.
enum class RidgeEstimator : uint8_t { kTensor, kFit };

/// Which lines to extract, and their thresholds (filled identically by CLI, scene file and
/// viewer; docs/design.md §4).
struct LineParams {
  bool contours = true;  ///< occluding contours, n·v = 0. Default on
  /// Keep contour points only where kr > 0 (trims the contour loops hidden behind the
  /// surface; docs/design.md §3.6). Default off.
  bool contours_require_positive_kr = false;
  /// Where a crease (below) is itself a silhouette — its two faces face opposite ways — the
  /// contour runs along the crease edge. Vertex normals average across a sharp edge, so the
  /// interpolated n·v = 0 would otherwise wander over the faces beside it, as far as a face's
  /// width on a coarse adapted mesh (a wavy, broken outline along a CAD part's sharp rim).
  /// The contour's n·v is set to 0 at the crease's vertices, so the one zero-set extractor
  /// puts the line on the edge and joins it to the smooth contour where that meets the
  /// crease (docs/lines.md). Default on.
  bool contours_follow_creases = true;
  bool suggestive = true;  ///< suggestive contours, kr = 0 where Dw kr > 0. Default on
  /// Keep suggestive points where tanθ·Dw kr > suggestive_threshold / fs² (fs = feature
  /// size). Default 0.01 (rtsc's default, with the same feature-size definition).
  float suggestive_threshold = 0.01f;
  /// Fade of weak suggestive lines: endpoint alpha = q/(q + fade/fs²·cosθ) with
  /// q = sinθ·Dw kr − threshold·cosθ, i.e. alpha → 0 where the test is barely passed.
  /// 0 disables fading (alpha 1). Default 0.03 (rtsc's "faded" style).
  float suggestive_fade = 0.03f;
  /// Suggestive contours and highlights leave out the faces with a corner on a crease line
  /// (the creases below, at the crease angle, marked or non-manifold). Curvature is not
  /// defined across a sharp edge, and the estimate there, averaged over both sides, is the
  /// crease itself: its kr zero set runs beside the crease as a row of scratches (CAD parts,
  /// docs/lines.md). The crease is drawn as a crease line. false: as rtsc draws them.
  bool suggestive_off_creases = true;
  /// Fading of suggestive contours that slide fast over the surface (DeCarlo, Finkelstein,
  /// Rusinkiewicz 2004, §4; docs/temporal-coherence.md): a line's alpha is multiplied by
  /// 1 − smoothstep(start, end, speed), speed being how fast the line crosses the surface in
  /// the image, px/s, estimated per vertex from the frame-to-frame change of the smoothed kr:
  /// |Δkr| / (Dw kr·Δt), seen foreshortened. Only in sequences (capture, the viewer) with
  /// temporal smoothing on; a still has no motion. end ≤ 0: off. Default off (it did not
  /// lower the churn of the captures measured; `--suggestive-motion-fade START,END`).
  float suggestive_motion_fade_start = 0.0f;
  float suggestive_motion_fade_end = 0.0f;
  /// Rejection near contours: no suggestive contour where n·v, interpolated along it, is below
  /// this. 0 keeps them to the front-facing surface, cut where a face straddling the contour
  /// turns away (rtsc leaves out only the faces entirely turned away); larger values also
  /// drop suggestive lines within asin(value) of grazing (where the angle between the normal
  /// and the view exceeds acos(value)). Default 0.
  float suggestive_min_ndotv = 0.0f;
  bool creases = true;  ///< edges with a dihedral angle above crease_angle_deg. Default on
  /// Angle between the two face normals above which an edge is a crease, degrees. Default 60.
  float crease_angle_deg = 60.0f;
  /// Also draw TriMesh::marked_edges (and non-manifold edges) as creases. Default on.
  bool marked_edges = true;
  bool boundaries = true;  ///< edges with one face. Default on
  // Level-set kinds (lines/level_lines.h, docs/lines.md). Off by default here; a drawing
  // turns each on when its style enables the kind (`--lines ...,isophote`).
  bool isophotes = false;  ///< n·l = k·isophote_spacing, k ≥ 0 (terminator and lit side)
  /// Spacing of the isophotes in n·l. Default 0.25 (n·l = 0, 0.25, 0.5, 0.75).
  float isophote_spacing = 0.25f;
  /// The light isophotes are of: towards the light, eye space (the frame's light,
  /// FrameParams::light_dir_eye, which the app copies here).
  glm::vec3 light_dir_eye{-0.45f, 0.6f, 0.65f};
  bool topo = false;  ///< topographic lines: heights along topo_axis at multiples of the spacing
  /// Spacing of the topographic lines as a fraction of the object's bounding-box diagonal
  /// (full detail), levels counted from the box's centre. Default 1/24.
  float topo_spacing = 1.0f / 24.0f;
  glm::vec3 topo_axis{0.0f, 1.0f, 0.0f};  ///< world up of the heights (normalised). Default +y
  bool parabolic = false;  ///< parabolic lines, K = k1·k2 = 0
  /// Parabolic lines only where max(|k1|, |k2|) > parabolic_threshold / fs, so flat parts,
  /// where K is 0 up to noise, draw none. fs, the feature size, is rtsc's: 1% of the
  /// reciprocal of the 10th-percentile curvature, so the default 0.05 keeps vertices curved
  /// more than 5× that percentile.
  float parabolic_threshold = 0.05f;
  /// Suggestive highlights (DeCarlo & Rusinkiewicz, "Highlight Lines for Conveying Shape",
  /// NPAR 2007, §3): kr = 0 where Dw kr < 0 — the maxima of n·v along ŵ that suggestive
  /// contours' minima mirror — with the same threshold and fade as suggestive contours, on
  /// −tanθ·Dw kr.
  bool suggestive_highlights = false;
  bool ridges = false;   ///< ridges (lines/ridge_lines.h)
  bool valleys = false;  ///< valleys (lines/ridge_lines.h)
  /// Ridges and valleys where the dominant curvature's |k|·fs exceeds this, faded in over
  /// one more threshold (fs as for parabolic lines: 0.1 is 10× the 10th-percentile
  /// curvature). Default 0.1.
  float ridge_threshold = 0.1f;
  /// Where ridges' and valleys' curvatures, directions and derivatives come from.
  /// kTensor (default): the per-face tensors every curvature kind shares (Rusinkiewicz 2004:
  /// fast, incremental, smoothed over time in sequences; it keeps features a couple of edges
  /// wide, but where k1 changes little across a line its derivative's noise draws spurious
  /// ridges). kFit: a degree-4 jet fitted over about 3 edges round each candidate vertex
  /// (shape/jet_fit.h: converges on smooth surfaces, ~10 µs a vertex; it smooths away
  /// features narrower than its disc). Either is smoothed over time in sequences.
  /// docs/lines.md compares them.
  RidgeEstimator ridge_estimator = RidgeEstimator::kTensor;
  bool apparent_ridges = false;  ///< apparent ridges (lines/ridge_lines.h)
  /// Apparent ridges where q1·fs (q1: the maximum view-dependent curvature) exceeds this,
  /// faded in over one more threshold. Default 0.1.
  float apparent_ridge_threshold = 0.1f;
  /// Material boundaries: edges whose two faces have different TriMesh::face_materials
  /// (Freestyle's and Line Art's "material boundaries"). On the adapted mesh they are exact
  /// too: a progressive mesh never collapses a vertex on one (pm/progressive_mesh.h).
  bool materials = false;
  bool principal_highlights = false;  ///< principal highlights (lines/ridge_lines.h)
  /// Principal highlights where (k_d² − k_o²)·n·v·fs² exceeds this, faded in over one more
  /// threshold (k_d, k_o: the dominant and the other principal curvature). Default 0.01.
  float principal_highlight_threshold = 0.01f;
  /// Also extract the mesh's own silhouette (edges between a front- and a back-facing face)
  /// each frame, so the presenter can draw it where the interpolated contour leaves the
  /// object's outline (coarse meshes; docs/visibility.md). Default on (`--outline complete`).
  bool complete_outline = true;
};

/// Extracted segments, flat arrays (caller-owned, reused between frames).
struct LineSet {
  std::vector<glm::vec3> points;    ///< 2 per segment, model units
  std::vector<float> alpha;         ///< 1 per point, in [0, 1] (fade; 1 when not faded)
  /// 1 per point: two points of the same type with equal id are the same point (exactly
  /// equal positions); used by chainStrokes(). Edge crossings use the edge index, zero-set
  /// points exactly at a vertex (its value is 0) edgeCount + the vertex index, points inside
  /// a face ids ≥ edgeCount + vertexCount; crease and boundary endpoints the vertex index.
  std::vector<uint32_t> point_ids;
  std::vector<LineKind> kinds;      ///< 1 per segment
  /// 1 per segment: the face it crosses (zero-set lines) or the edge it lies on (creases,
  /// boundaries).
  std::vector<uint32_t> sources;
  std::array<uint32_t, kLineKindCount> counts{};  ///< segments per LineKind

  size_t segmentCount() const { return kinds.size(); }
  void clear();
};

/// Appends one segment (p0 → p1, ids and alphas per endpoint) of kind `type` from face or
/// edge `source` to `out`.
[[gnu::always_inline]] inline void pushSegment(LineSet& out, LineKind type, uint32_t source, const glm::vec3& p0,
                                               uint32_t id0, float a0, const glm::vec3& p1, uint32_t id1, float a1) {
  out.points.push_back(p0);
  out.points.push_back(p1);
  out.alpha.push_back(a0);
  out.alpha.push_back(a1);
  out.point_ids.push_back(id0);
  out.point_ids.push_back(id1);
  out.kinds.push_back(type);
  out.sources.push_back(source);
  ++out.counts[static_cast<int>(type)];
}

/// Input of the generic zero-set extractor. Spans hold vertexCount floats (or are empty).
struct ZeroSetInput {
  std::span<const float> value;     ///< the line is where it changes sign (< 0 vs ≥ 0)
  std::span<const float> test_num;  ///< optional: keep points where num/den > 0
  std::span<const float> test_den;  ///< optional (empty: den = 1)
  /// Optional: no line where the gate, interpolated along it like the test, is below
  /// gate_min (a face with every corner below has none; one with some is cut where the
  /// interpolated gate crosses gate_min, so the line shortens as the gate moves instead of
  /// leaving a whole face at once).
  std::span<const float> gate;
  float gate_min = 0.0f;
  /// Optional (vertexCount bytes): skip faces with any vertex non-zero here (the whole face,
  /// unlike the gate).
  std::span<const uint8_t> shut;
  float fade = 0.0f;  ///< > 0: endpoint alpha = num/(num + fade·den), clamped; 0: alpha 1
  /// Optional: per-vertex factor in [0, 1] on the alpha (interpolated like the test).
  std::span<const float> gain;
  /// Leave out segments that join two vertices whose value is exactly 0 (the caller draws
  /// the edges it means itself: the contour along silhouette creases).
  bool skip_vertex_pairs = false;
};

/// Scratch buffers of the extractors (per-edge crossings, marks); reuse between calls.
struct LineScratch {
  std::vector<uint8_t> vertex_code;  // per vertex: value sign, test, gate (extractZeroSet)
  std::vector<uint8_t> edge_mark;           // per edge: 1 crease, 2 boundary, 0 neither
  std::vector<uint32_t> marked_edges;       // the edges edge_mark marks, in edge order
  std::vector<float> contour_value;         // n·v with silhouette creases' vertices at 0
  std::vector<uint32_t> silhouette_creases;  // their edges
  std::vector<uint8_t> vertex_ends;          // contour ends per vertex (spurs along creases)
  std::vector<uint8_t> crease_vertex;        // vertices on a crease edge (suggestive_off_creases)
  std::vector<int8_t> face_facing;           // per face: 1 front, -1 back, 0 degenerate
  std::vector<uint8_t> silhouette_edge;      // per edge: 1 on the mesh's silhouette
  uint32_t next_interior_id = 0;
  /// Optional threads (not owned) for the per-edge and per-face passes; the output is the
  /// same.
  WorkerPool* pool = nullptr;
  std::vector<LineSet> part_sets;       // per-face pass, one set per part
  std::vector<uint32_t> part_interior;  // interior ids each part used
  /// The per-face pass finds the faces with a line sixteen at a time where the processor has
  /// AVX-512 (the same faces, in the same order); false scans them one by one (tests compare).
  bool wide_face_scan = true;
};

/// Appends to `out` the segments of the zero set of `in.value` over the valid faces of
/// (positions, faces), typed `type`. `adjacency` must be built from the same faces.
/// Exactly extractZeroSets() with one input.
void extractZeroSet(std::span<const glm::vec3> positions,
                    std::span<const std::array<uint32_t, 3>> faces,
                    const MeshAdjacency& adjacency, const ZeroSetInput& in, LineKind type,
                    LineScratch& scratch, LineSet& out);

/// The zero sets of several inputs, inputs[k] typed types[k], in one pass over the faces
/// (two at a time): the same segments, in the same order and with the same point ids, as
/// extractZeroSet() called on each in turn. Inputs whose value does not hold one float per
/// vertex are skipped.
void extractZeroSets(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> faces,
                     const MeshAdjacency& adjacency, std::span<const ZeroSetInput> inputs,
                     std::span<const LineKind> types, LineScratch& scratch, LineSet& out);

/// Appends a LineKind::kMaterial segment for every edge whose two faces have different
/// mesh.face_materials (nothing when that is empty); endpoint ids the vertex indices.
void extractMaterialLines(const TriMesh& mesh, const MeshAdjacency& adjacency, LineSet& out);

/// Appends creases (dihedral angle, marked and non-manifold edges) and boundaries, as
/// enabled in `params`. `face_normals` holds faceCount unit normals (zero: degenerate, never
/// a crease).
/// `crease_vertices` (optional, vertexCount bytes): a dihedral-angle crease needs both ends
/// non-zero. Level of detail passes the vertices that lie on a crease at full detail, so the
/// sharp dihedral angles a coarse mesh has on smooth curved parts draw no false creases.
void extractEdgeLines(const TriMesh& mesh, const MeshAdjacency& adjacency,
                      std::span<const glm::vec3> face_normals, const LineParams& params,
                      LineScratch& scratch, LineSet& out,
                      std::span<const uint8_t> crease_vertices = {});

/// Clears `out` and appends the mesh's own silhouette as seen from `view`: the manifold
/// edges whose two valid faces face opposite ways (one front-, one back-facing), typed
/// kContour with the vertex indices as point ids, so chainStrokes() joins them. On a coarse
/// mesh this polygonal outline is where the faces as drawn end, while the interpolated
/// contour (n·v = 0 on vertex normals) may run inside it (docs/visibility.md).
/// `face_normals` holds faceCount unit normals (zero: degenerate, skipped). `scratch` holds
/// each face's facing and each edge's mark between the passes (on scratch.pool's threads
/// where set; the output is the same).
void extractMeshSilhouette(const TriMesh& mesh, const MeshAdjacency& adjacency,
                           std::span<const glm::vec3> face_normals, const ViewSpec& view, LineScratch& scratch,
                           LineSet& out);

/// Clears `out` and extracts every enabled line type from precomputed view quantities.
/// `feature_size` (model units, > 0) scales the suggestive thresholds by 1/fs².
/// `suggestive_gain` (optional, vertexCount entries in [0, 1]) multiplies the suggestive
/// contours' alpha (the motion fade, suggestiveMotionGain()).
void extractLines(const TriMesh& mesh, const MeshAdjacency& adjacency,
                  std::span<const glm::vec3> face_normals, const ViewQuantities& view,
                  const LineParams& params, float feature_size, LineScratch& scratch,
                  LineSet& out, std::span<const uint8_t> crease_vertices = {},
                  std::span<const float> suggestive_gain = {});

/// Stateful convenience: view quantities + extraction with reused buffers.
///
///   LineExtractor lines;
///   lines.extract(mesh, shape, ViewSpec::fromCamera(cam), params, fs, line_set);
class LineExtractor {
 public:
  /// `shape` must have been computed on `mesh`. Allocation-free after warm-up.
  void extract(const TriMesh& mesh, const ShapeCache& shape, const ViewSpec& view,
               const LineParams& params, float feature_size, LineSet& out);
  /// Same, with caller-supplied per-vertex fields (e.g. temporally smoothed normals).
  void extract(const TriMesh& mesh, const ShapeCache& shape, const SurfaceFields& fields,
               const ViewSpec& view, const LineParams& params, float feature_size,
               LineSet& out);
  /// The quantities of the last extract().
  const ViewQuantities& viewQuantities() const { return view_; }

 private:
  ViewQuantities view_;
  LineScratch scratch_;
};

}  // namespace lodline
