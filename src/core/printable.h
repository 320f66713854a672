// Text from the outside world (a file's bytes, a parser's message that quotes them, an option
// value) made safe to echo in a one-line error: docs/design.md §6.
#pragma once

#include <string>
#include <string_view>

namespace lodline {

/// `text` made fit for a one-line error: control characters and non-ASCII bytes become '?',
/// and it is cut to `max_chars` ("...").
std::string printableText(std::string_view text, size_t max_chars = 200);

}  // namespace lodline
