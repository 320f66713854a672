// One still frame of a loaded scene, end to end: the detail converged for the camera (the
// picture a viewer settles on), drawn by a presenter, written as PNG, SVG and `--stats` JSON
// (docs/stats.md). What `lodline render` does after parsing its options.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/image.h"
#include "core/result.h"
#include "frame/scene_builder.h"
#include "gl/context.h"
#include "present/presenter.h"

namespace lodline {

struct StillRequest {
  PresenterBackend backend = PresenterBackend::kGl;
  ContextBackend context = ContextBackend::kAuto;
  std::filesystem::path png;    ///< empty: none
  std::filesystem::path svg;    ///< empty: none
  std::filesystem::path stats;  ///< empty: none
  double elapsed_ms = 0.0;      ///< time the caller spent before (loading), for ms.total
};

/// A still drawn by drawStill().
struct StillFrame {
  Camera camera;
  Image image;          ///< colour, row 0 = top
  int adapt_steps = 0;  ///< adaptation steps to converge
  double ms_adapt = 0.0;
};

/// Converges `loaded`'s detail at its initial camera and draws it with `presenter` (made for
/// loaded.view.frame) as a frame of its own (a new sequence), then computes the visible
/// strokes. Errors: the camera, the adaptation, a style the presenter cannot draw.
Result<StillFrame> drawStill(LoadedScene& loaded, ScenePresenter& presenter);

/// The `--stats` JSON of a still drawn by drawStill() (docs/stats.md): `ms_setup` the
/// presenter's creation, `ms_before` the time spent before drawStill (loading).
nlohmann::json stillStats(const LoadedScene& loaded, ScenePresenter& presenter, const StillFrame& still,
                          double ms_setup, double ms_before);

/// Converges `loaded`'s detail at its initial camera, draws it and writes the requested
/// outputs (each atomically). Errors: no context, a style the backend cannot draw (usage),
/// unwritable outputs.
Status renderStill(LoadedScene& loaded, const StillRequest& request);

}  // namespace lodline
