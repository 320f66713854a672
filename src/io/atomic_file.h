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

/// Removes the temporary files a process that died (SIGKILL, a crash, power loss) left next
/// to `path`: writeFileAtomically's ".NAME.tmpPID-N" and VideoWriter's ".NAME.partPID.mp4",
/// where no process PID exists any more. Files of running processes are kept. Called before
/// `path` is written again (and by the progressive-mesh cache when it reads), so leftovers
/// do not pile up.
void removeStaleTemporaries(const std::filesystem::path& path);

/// Checks early that `path` can be created (its directory exists and is writable), so a
/// long render fails before it starts. Error names the path.
Status checkWritable(const std::filesystem::path& path);

}  // namespace lodline
