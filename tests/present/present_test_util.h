// Helpers of the present/ tests: one mesh as a scene, drawn through a presenter.
#pragma once

#include <memory>
#include <string>

#include "frame/scene_drawing.h"
#include "io/image.h"
#include "present/presenter.h"
#include "test_util.h"

namespace lodline::test {

/// A scene of `mesh` at full detail, in `style`.
inline SceneDrawing sceneOf(TriMesh mesh, const ObjectStyle& style, const std::string& name = "mesh") {
  SceneDrawing scene;
  SceneDrawing::Object o;
  o.name = name;
  o.style = style;
  o.input_faces = mesh.faceCount();
  o.input_vertices = mesh.vertexCount();
  o.drawing = std::make_unique<LodDrawing>(std::move(mesh));
  scene.add(std::move(o));
  return scene;
}

/// What a presenter drew.
struct Presented {
  std::unique_ptr<ScenePresenter> presenter;
  Image image;
  std::string error;  ///< why nothing was drawn (no context)
  explicit operator bool() const { return presenter != nullptr; }
};

/// Computes `scene`'s lines for `camera` and presents it on `backend` (GL through a headless
/// `context`); empty with the reason when no presenter can be made.
inline Presented presentScene(SceneDrawing& scene, const Camera& camera, const FrameParams& frame,
                              PresenterBackend backend = PresenterBackend::kGl,
                              ContextBackend context = ContextBackend::kEgl) {
  Presented out;
  auto p = createPresenter(backend, context, scene, frame);
  if (!p) {
    out.error = p.error().message;
    return out;
  }
  if (Status s = scene.frame(camera, frame.width, frame.height, DetailParams{}, 1.0f / 30.0f); !s) {
    out.error = s.error().message;
    return out;
  }
  if (Status s = (*p)->present(scene, camera, frame, true); !s) {
    out.error = s.error().message;
    return out;
  }
  out.image = (*p)->readImage();
  out.presenter = std::move(p.value());
  return out;
}

}  // namespace lodline::test
