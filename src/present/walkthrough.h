// The walkthrough benchmark of Pan, Zhou, Shi, "Real-time rendering algorithm based on hybrid
// static and dynamic simplification methods" (their Table 2; docs/design.md §2.4), on
// today's machine. One camera path is replayed for several levels of detail, side by side in
// one run:
//   none     the full-detail mesh;
//   cluster  view-dependent vertex clustering every frame (src/lod/vertex_clustering.h);
//   hybrid   static pre-simplification within a bound of the diagonal (E_s measured with
//            CGAL), then clustering;
//   pm       the progressive mesh with image-area detail control (Jeong et al. 2005).
// A frame is the CPU stages (LOD, shape, lines) plus presenting it (upload, draw to
// glFinish), headless, with the scene's styles and light. Each mode rebuilds the scene with
// the builder every command uses (frame/scene_builder.h).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/result.h"
#include "frame/camera_path.h"
#include "frame/scene_builder.h"
#include "gl/context.h"

namespace lodline {

struct WalkthroughRequest {
  std::vector<std::string> modes{"none", "cluster", "hybrid", "pm"};
  /// The camera path, made around the first mode's scene (every mode has the same bounds).
  PathChoice path;
  int frames = 60;        ///< frames replayed per mode, evenly over the path
  float pixel_error = 1.0f;  ///< clustering's K, px²
  double pre_simplify = 0.0002;  ///< hybrid: static E_s bound, fraction of the diagonal
  ContextBackend context = ContextBackend::kAuto;
  /// Non-empty: each mode's first frame (converged at the path's first camera, untimed) is
  /// written as PREFIX-MODE.png, to compare a benchmark frame with `render`.
  std::string snapshot_prefix;
};

/// One mode's figures.
struct WalkthroughResult {
  std::string mode;
  double mean_ms = 0.0, cpu_ms = 0.0, gl_ms = 0.0;
  double faces = 0.0;      ///< mean triangles drawn per frame
  size_t model_faces = 0;  ///< faces of the meshes the mode starts from
  double setup_s = 0.0;    ///< load + preprocessing (PM build or cache, pre-simplification)
  std::string note;
};

/// Replays the path for each mode and writes the markdown table (and the ratios to no LOD)
/// to `out`; progress lines go to stderr. `input` gives the scene, its styles, frame (light
/// included) and detail parameters; its level of detail is replaced by each mode's
/// (the progressive mesh's cache folder is kept).
Result<std::vector<WalkthroughResult>> runWalkthrough(const SceneInput& input, const WalkthroughRequest& request,
                                                      std::ostream& out);

/// "none", "cluster", "hybrid" or "pm"; a usage error otherwise.
Status checkWalkthroughMode(const std::string& mode);

}  // namespace lodline
