// Progressive mesh cache file: compact, versioned, checksummed binary (little-endian).
//
// Layout (version 1): a 64-byte header {magic "LODLPM\0\x1a", version, vertex/face/split/
// base-face counts, content hash, build-params hash, payload size, checksum} followed by the
// payload: positions (3 f32 per vertex), faces (3 u32 per face), vertex flags (1 byte per
// vertex, padded to 4), splits (8 u32 each), base face ids, base corners, base neighbours.
// The checksum (hashBytes) covers the header (checksum field zeroed) and the payload.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/mesh.h"
#include "core/result.h"
#include "pm/progressive_mesh.h"

namespace lodline {

/// Current file format version.
inline constexpr uint32_t kPmFileVersion = 1;

/// Writes `pm` to `path` atomically (temporary file, then rename). Errors name the path.
Status savePm(const std::filesystem::path& path, const ProgressiveMesh& pm);

/// Reads a file written by savePm. Errors name the path and the problem: missing file, wrong
/// magic, unsupported version, truncation, checksum mismatch, indices out of range. Never
/// crashes on hostile input.
Result<ProgressiveMesh> loadPm(const std::filesystem::path& path);

/// Cache file name for a model: "<16 hex digits of content_hash>.lpm" in `cache_dir`.
std::filesystem::path pmCachePath(const std::filesystem::path& cache_dir, uint64_t content_hash);

/// Loads the cached progressive mesh of `mesh` from `cache_dir` when it is there, intact and
/// built from the same content (`content_hash`, usually meshContentHash(mesh) or the model
/// file's hash) with the same params; otherwise builds it and (re)writes the cache (creating
/// `cache_dir` if needed). A cache that cannot be written is not an error: `note` (optional)
/// then says so. `note` receives one line describing what happened ("loaded ...", "cache
/// stale, rebuilt ...", "cache unreadable (...), rebuilt ...").
Result<ProgressiveMesh> loadOrBuildPm(const TriMesh& mesh, uint64_t content_hash,
                                      const std::filesystem::path& cache_dir,
                                      const PmBuildParams& params = {},
                                      const PmProgress& progress = {},
                                      std::string* note = nullptr);

}  // namespace lodline
