#include "present/soft_presenter.h"

namespace lodline {

SoftPresenter::SoftPresenter(std::shared_ptr<WorkerPool> pool) {
  if (pool) renderer_.setWorkerPool(std::move(pool));
}

Status SoftPresenter::check(const SceneDrawing& scene) const {
  for (const auto& o : scene.objects())
    if (Status s = SoftRenderer::supports(o.style); !s)
      return Error::usage("--backend soft: object '" + o.name + "': " + s.error().message + " (use --backend gl)");
  return {};
}

Status SoftPresenter::uploadMeshes(const SceneDrawing& scene, bool all_meshes) {
  if (renderer_.objectCount() != scene.size()) {
    renderer_.setObjectCount(scene.size());
    all_meshes = true;
  }
  for (size_t i = 0; i < scene.size(); ++i) {
    const LodDrawing& d = *scene[i].drawing;
    const LineDrawing& ld = d.drawing();
    if (all_meshes || d.meshChanged()) renderer_.setMesh(i, ld.mesh().positions, ld.normals(), ld.mesh().faces);
    renderer_.setBackFaceCulling(i, d.backFacesHidden(), d.bounds().center, d.bounds().radius);
  }
  return {};
}

Status SoftPresenter::drawSurfaces(const Camera& camera, const FrameParams& frame,
                                   std::span<const ObjectStyle> styles) {
  renderer_.drawSurfaces(camera, frame, styles);
  return {};
}

Status SoftPresenter::readSurface(SurfaceImage& out) {
  renderer_.drawSurface(camera(), out);
  return {};
}

}  // namespace lodline
