#include "present/still.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/timer.h"
#include "io/atomic_file.h"
#include "io/image.h"
#include "present/frame_report.h"
#include "present/soft_presenter.h"
#include "present/svg_output.h"

namespace lodline {
namespace {

// Pixels that differ from the background: the image area the model covers (what detail
// control divides by T).
uint64_t coveragePixels(const Image& image, const glm::vec4& background) {
  const int bg[3] = {static_cast<int>(std::lround(background.r * 255.0f)),
                     static_cast<int>(std::lround(background.g * 255.0f)),
                     static_cast<int>(std::lround(background.b * 255.0f))};
  uint64_t n = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    const int d = std::max({std::abs(image.rgba[i] - bg[0]), std::abs(image.rgba[i + 1] - bg[1]),
                            std::abs(image.rgba[i + 2] - bg[2])});
    n += d > 8;
  }
  return n;
}

}  // namespace

Result<StillFrame> drawStill(LoadedScene& loaded, ScenePresenter& p) {
  Stopwatch stage;
  SceneDrawing& scene = loaded.drawing;
  const FrameParams& frame = loaded.view.frame;
  StillFrame still;
  auto camera = initialCamera(loaded, frame.aspect());
  if (!camera) return camera.error();
  still.camera = *camera;
  // A still image shows the converged detail.
  auto steps = scene.converge(*camera, frame.width, frame.height, loaded.detail.params, SceneDrawing::kConvergeStepSeconds,
                              loaded.detail.max_adapt_frames);
  if (!steps) return steps.error();
  still.adapt_steps = *steps;
  still.ms_adapt = stage.lap();
  p.startSequence(false);
  if (Status s = p.present(scene, *camera, frame, true); !s) return s.error();
  still.image = p.readImage();
  // Visible strokes of every object, from the depth of all faces (so one object hides
  // another's lines): for the SVG and the stats.
  (void)p.visible();
  return still;
}

nlohmann::json stillStats(const LoadedScene& loaded, ScenePresenter& p, const StillFrame& still, double ms_setup,
                          double ms_before) {
  Stopwatch total;
  const SceneDrawing& scene = loaded.drawing;
  const FrameParams& frame = loaded.view.frame;
  const FrameReport report = reportFrame(scene, p);
  nlohmann::json j;
  j["model"] = {{"path", loaded.view.model.string()},
                {"vertices", report.total.input_vertices},
                {"faces", report.total.input_faces}};
  j["image"] = {{"width", frame.width}, {"height", frame.height},
                {"coverage_px", coveragePixels(still.image, frame.background)}};
  const bool soft = p.backendName() == "soft";
  j["context"] = {{"backend", p.backendName()}, {"gl", soft ? std::string("none") : p.description()}};
  j.update(frameStatsJson(report));
  if (j.contains("lod")) {
    j["lod"]["target_area"] = loaded.detail.params.target_area * loaded.detail.params.object_factor;
    j["lod"]["adapt_steps"] = still.adapt_steps;
    j["lod"]["cache"] = loaded.build.cache_note;
  }
  if (const auto* sp = dynamic_cast<const SoftPresenter*>(&p)) {
    const SoftTimes& st = sp->softTimes();
    j["soft_ms"] = {{"transform", st.transform}, {"setup", st.setup}, {"raster", st.raster},
                    {"shade", st.shade},         {"lines", st.lines}};
  }
  const StageTimes& ms = report.ms;
  j["ms"] = {{"load", loaded.build.load_ms},
             {"intersect", loaded.build.intersect_ms},
             {"pm", loaded.build.pm_ms},
             {"adapt", still.ms_adapt},
             {"shape", ms.shape},
             {"view", ms.view},
             {"extract", ms.extract},
             {"chain", ms.chain},
             {"setup", ms_setup + ms.upload},
             {"render", ms.render},
             {"readback", ms.readback},
             {"visibility", ms.visibility},
             {"strokes", ms.strokes},
             {"total", ms_before + total.elapsed()}};
  return j;
}

Status renderStill(LoadedScene& loaded, const StillRequest& request) {
  Stopwatch total, stage;
  auto presenter = createPresenter(request.backend, request.context, loaded.drawing, loaded.view.frame);
  if (!presenter) return presenter.error();
  ScenePresenter& p = **presenter;
  const double ms_context = stage.lap();
  auto still = drawStill(loaded, p);
  if (!still) return still.error();
  if (!request.png.empty())
    if (Status s = writePng(request.png, still->image); !s) return s;
  if (!request.svg.empty())
    if (Status s = writeFrameSvg(request.svg, loaded.drawing, p); !s) return s;
  if (request.stats.empty()) return {};
  const nlohmann::json j = stillStats(loaded, p, *still, ms_context, request.elapsed_ms + total.elapsed());
  const std::string text = j.dump(2) + "\n";
  return writeFileAtomically(request.stats, [&](std::ostream& out) -> Status {
    out << text;
    return {};
  });
}

}  // namespace lodline
