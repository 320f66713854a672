// One still frame of a loaded scene, end to end: the detail converged for the camera (the
// picture a viewer settles on), drawn by a presenter, written as PNG, SVG and `--stats` JSON
// (docs/stats.md). What `lodline render` does after parsing its options.
#pragma once

#include <filesystem>

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

/// Converges `loaded`'s detail at its initial camera, draws it and writes the requested
/// outputs (each atomically). Errors: no context, a style the backend cannot draw (usage),
/// unwritable outputs.
Status renderStill(LoadedScene& loaded, const StillRequest& request);

}  // namespace lodline
