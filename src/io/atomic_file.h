// Writing outputs so a failure never leaves a half-written file: write into a temporary
// file next to the target, then rename over it (atomic on POSIX file systems).
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

#include "core/result.h"

namespace lodline {

/// Calls `write` with a stream on a temporary file in `path`'s directory; on success
/// (write returns ok and the stream is good) renames it to `path`, otherwise removes it.
/// Errors name `path`.
Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(std::ostream&)>& write);

/// Checks early that `path` can be created (its directory exists and is writable), so a
/// long render fails before it starts. Error names the path.
Status checkWritable(const std::filesystem::path& path);

}  // namespace lodline
