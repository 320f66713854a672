// Joining the outputs of a capture rendered in shards (`capture --frames A:B` on several
// machines or processes; docs/capture.md): MP4s without re-encoding (ffmpeg's concat
// demuxer), folders of numbered frames (PNG or SVG), and the per-frame metrics CSVs. Each
// join checks that the shards fit: the same columns, frames neither repeated nor missing.
// Every output is written atomically.
#pragma once

#include <filesystem>
#include <span>

#include "core/result.h"

namespace lodline {

/// Concatenates MP4 files, in the order given, into `out` with ffmpeg's concat demuxer and
/// stream copy (no re-encoding). Errors name the part ffmpeg rejected, or ffmpeg missing.
Status joinVideos(std::span<const std::filesystem::path> parts, const std::filesystem::path& out);

/// Copies the frame_NNNNN.png / .svg files of the folders `parts` into the folder `out`
/// (created). Errors: a frame in two parts, a gap between parts, a folder without frames.
Status joinFrameFolders(std::span<const std::filesystem::path> parts, const std::filesystem::path& out);

/// Joins `capture --metrics` CSVs: the same header in every part, rows ordered by frame,
/// frames contiguous from the first part's first. Errors name the part and the frame.
Status joinMetricsCsv(std::span<const std::filesystem::path> parts, const std::filesystem::path& out);

}  // namespace lodline
