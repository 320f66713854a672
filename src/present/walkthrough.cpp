#include "present/walkthrough.h"

#include <iomanip>
#include <iostream>
#include <sstream>

#include "cgal/simplify.h"
#include "core/timer.h"
#include "io/image.h"
#include "present/presenter.h"

namespace lodline {

Status checkWalkthroughMode(const std::string& mode) {
  if (mode == "none" || mode == "cluster" || mode == "hybrid" || mode == "pm") return {};
  return Error::usage("--modes: unknown mode '" + mode + "' (none, cluster, hybrid, pm)");
}

Result<std::vector<WalkthroughResult>> runWalkthrough(const SceneInput& input, const WalkthroughRequest& rq,
                                                      std::ostream& out) {
  const FrameParams& frame = input.view.frame;
  ProgressiveDetail pm_choice;
  if (const auto* pm = std::get_if<ProgressiveDetail>(&input.detail.lod)) pm_choice = *pm;
  size_t input_faces = 0;
  CameraPath path;
  std::unique_ptr<ScenePresenter> presenter;
  std::vector<WalkthroughResult> results;
  for (const std::string& mode : rq.modes) {
    if (Status s = checkWalkthroughMode(mode); !s) return s.error();
    WalkthroughResult r;
    r.mode = mode;
    Stopwatch sw;
    ClusteredDetail cluster;
    cluster.params.pixel_error = rq.pixel_error;
    LodChoice lod = pm_choice;
    MeshPrepare prepare;
    if (mode == "none") lod = FullDetail{};
    if (mode == "cluster" || mode == "hybrid") lod = cluster;
    if (mode == "hybrid") {
      prepare = [&](TriMesh mesh, const SceneObject& obj) -> Result<TriMesh> {
        auto s = simplifyMesh(mesh, rq.pre_simplify, obj.mesh.string());
        if (!s) return s.error();
        std::ostringstream note;
        note << (r.note.empty() ? "" : "; ") << "pre-simplified " << mesh.faceCount() << " -> " << s->mesh.faceCount()
             << " faces, E_s " << std::setprecision(3) << 100.0 * s->e_s_rel << "%";
        r.note += note.str();
        r.model_faces += s->mesh.faceCount();
        return std::move(s->mesh);
      };
    }
    SceneBuildInfo info;
    auto scene = buildSceneDrawing(input.scene, input.styles, lod, input.view.line_params, info, prepare, {},
                                   input.intersections);
    if (!scene) return scene.error();
    input_faces = scene->inputFaceCount();
    if (mode != "hybrid") r.model_faces = scene->inputFaceCount();
    if (mode == "pm") r.note = info.cache_note;
    if (!presenter) {
      auto p = createPresenter(PresenterBackend::kGl, rq.context, *scene, frame);
      if (!p) return p.error();
      presenter = std::move(p.value());
      auto cam_path = scenePath(rq.path, scene->bounds(), input.scene.camera, input.view.fov_deg, frame.aspect(),
                                input.view.orbit);
      if (!cam_path) return cam_path.error();
      path = std::move(cam_path.value());
    }
    const DetailParams& detail = input.detail.params;
    const double dt = path.duration() / (rq.frames - 1);
    // Warm-up (not timed): the progressive mesh converges at the first camera, as a viewer
    // would before the walk starts (with render's step, so the first frame is its still); every
    // mode uploads its first mesh.
    const Camera first = path.at(path.keys().front().time, scene->bounds());
    if (auto st = scene->converge(first, frame.width, frame.height, detail, SceneDrawing::kConvergeStepSeconds,
                                  input.detail.max_adapt_frames);
        !st)
      return st.error();
    presenter->startSequence(false);  // each mode starts afresh: its first frame is render's still
    if (Status st = presenter->present(*scene, first, frame, true); !st) return st.error();
    r.setup_s = sw.lap() / 1000.0;
    if (!rq.snapshot_prefix.empty())
      if (Status st = writePng(rq.snapshot_prefix + "-" + mode + ".png", presenter->readImage()); !st)
        return st.error();
    double total = 0.0, cpu = 0.0, faces = 0.0;
    for (int i = 0; i < rq.frames; ++i) {
      const double t = path.keys().front().time + i * dt;
      const Camera cam = path.at(t, scene->bounds());
      Stopwatch frame_clock;
      if (Status st = scene->frame(cam, frame.width, frame.height, detail, static_cast<float>(dt)); !st)
        return st.error();
      const double c = frame_clock.elapsed();
      if (Status st = presenter->present(*scene, cam, frame, false); !st) return st.error();
      total += frame_clock.elapsed();
      cpu += c;
      for (size_t o = 0; o < scene->size(); ++o) faces += static_cast<double>(presenter->facesDrawn(o));
    }
    r.mean_ms = total / rq.frames;
    r.cpu_ms = cpu / rq.frames;
    r.gl_ms = r.mean_ms - r.cpu_ms;
    r.faces = faces / rq.frames;
    results.push_back(r);
    std::cerr << "lodline: " << mode << ": " << std::fixed << std::setprecision(1) << 1000.0 / r.mean_ms << " fps\n";
  }

  const size_t objects = input.scene.objects.size();
  out << "Walkthrough of " << input.view.model.string() << " (" << input_faces << " faces"
      << (objects > 1 ? " in " + std::to_string(objects) + " objects" : std::string()) << "), path " << rq.path.name_or_file
      << ", " << rq.frames << " frames at " << frame.width << "x" << frame.height << ", msaa " << frame.msaa
      << ", pixel error " << rq.pixel_error << " px^2, T " << input.detail.params.target_area << " px^2; "
      << (presenter ? presenter->description() : std::string()) << "\n\n";
  out << "| mode | mean fps | ms/frame | CPU ms | GL ms | triangles drawn | mesh faces | setup s | note |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& r : results) {
    out << std::fixed << "| " << r.mode << " | " << std::setprecision(2) << 1000.0 / r.mean_ms << " | "
        << std::setprecision(1) << r.mean_ms << " | " << r.cpu_ms << " | " << r.gl_ms << " | " << std::setprecision(0)
        << r.faces << " | " << r.model_faces << " | " << std::setprecision(2) << r.setup_s << " | " << r.note << " |\n";
  }
  if (results.size() > 1 && results[0].mode == "none") {
    out << "\nfps ratios to no LOD:";
    for (size_t i = 1; i < results.size(); ++i)
      out << ' ' << results[i].mode << ' ' << std::setprecision(2) << results[0].mean_ms / results[i].mean_ms << 'x';
    out << " (Pan et al. 1999, bunny at 1 px: cluster 2.48x, hybrid 6.78x)\n";
  }
  return results;
}

}  // namespace lodline
