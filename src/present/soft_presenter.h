// The software presenter (`--backend soft`): raster/soft_renderer.h, no OpenGL context. It
// draws the lines and toon styles of any number of objects; the shaded style and chamfer
// highlights need OpenGL and are refused by check() with a usage error.
#pragma once

#include <memory>

#include "present/presenter.h"
#include "raster/soft_renderer.h"

namespace lodline {

class SoftPresenter final : public ScenePresenter {
 public:
  /// `pool` runs the rasteriser's loops (null: a pool of its own).
  explicit SoftPresenter(std::shared_ptr<WorkerPool> pool = nullptr);

  Status check(const SceneDrawing& scene) const override;
  Status readSurface(SurfaceImage& out) override;
  size_t facesDrawn(size_t object) const override { return renderer_.faceCount(object); }
  size_t segmentsDrawn(size_t object) const override { return renderer_.segmentsDrawn(object); }
  std::string backendName() const override { return "soft"; }
  std::string description() const override { return "none (software rasteriser)"; }
  /// Per-stage milliseconds of the last draw.
  const SoftTimes& softTimes() const { return renderer_.times(); }

 protected:
  Status uploadMeshes(const SceneDrawing& scene, bool all_meshes) override;
  Status drawSurfaces(const Camera& camera, const FrameParams& frame, std::span<const ObjectStyle> styles) override;
  void readDepth(DepthImage& out) override { out = renderer_.depth(); }
  void uploadLines(size_t object, const ScreenLines& lines) override { renderer_.setLines(object, lines); }
  void drawLines(const FrameParams& frame, std::span<const ObjectStyle> styles) override {
    renderer_.drawLines(frame, styles);
  }
  Image readColour() override { return renderer_.image(); }

 private:
  SoftRenderer renderer_;
};

}  // namespace lodline
