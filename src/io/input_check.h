// Checks on an input path before a reader opens it: a FIFO or a device would block or never
// end, a directory opens but reads nothing, and an unreadable file should say so rather than
// look empty or corrupt.
#pragma once

#include <filesystem>
#include <string>

#include "core/result.h"

namespace lodline {

/// Ok when `path` is a regular file (symlinks followed) that this process can open for
/// reading. Otherwise a runtime error naming the path: "no such file", "is a directory, not
/// a <what>", "is not a regular file (a FIFO, device or socket)", "cannot open for reading:
/// <reason>". `what` names the expected content ("mesh file", "PNG image", ...).
Status checkInputFile(const std::filesystem::path& path, const std::string& what);

}  // namespace lodline
