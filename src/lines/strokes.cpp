#include "lines/strokes.h"

#include <algorithm>

#include "core/result.h"

namespace lodline {

void StrokeSet::clear() {
  points.clear();
  alpha.clear();
  offsets.clear();
  types.clear();
  closed.clear();
}

namespace {
constexpr uint32_t kNone = 0xffffffffu;
constexpr uint64_t kEndBits = 30;  // endpoint index bits in a sort key
constexpr uint64_t kEndMask = (uint64_t{1} << kEndBits) - 1;
}  // namespace

void chainStrokes(const LineSet& lines, StrokeSet& out, ChainScratch& scratch) {
  out.clear();
  const size_t ns = lines.segmentCount();
  const size_t nends = 2 * ns;
  LODLINE_ASSERT(nends <= kEndMask);
  // Sort ends by (type, point id); key = type(2 bits) | id(32 bits) | end index(30 bits).
  scratch.keys.resize(nends);
  for (size_t k = 0; k < nends; ++k) {
    const uint64_t type = static_cast<uint64_t>(lines.types[k / 2]);
    scratch.keys[k] = (type << 62) | (uint64_t{lines.point_ids[k]} << kEndBits) | k;
  }
  std::sort(scratch.keys.begin(), scratch.keys.end());
  scratch.partner.assign(nends, kNone);
  for (size_t i = 0; i < nends;) {
    size_t j = i + 1;
    while (j < nends && (scratch.keys[j] >> kEndBits) == (scratch.keys[i] >> kEndBits)) ++j;
    if (j - i == 2) {
      const uint32_t a = static_cast<uint32_t>(scratch.keys[i] & kEndMask);
      const uint32_t b = static_cast<uint32_t>(scratch.keys[i + 1] & kEndMask);
      if (a / 2 != b / 2) {  // a degenerate segment joining a point to itself stays alone
        scratch.partner[a] = b;
        scratch.partner[b] = a;
      }
    }
    i = j;
  }

  scratch.used.assign(ns, 0);
  auto emit = [&](uint32_t end) {
    out.points.push_back(lines.points[end]);
    out.alpha.push_back(lines.alpha[end]);
  };
  // Walks from segment end `start` (its segment unused) along partners; returns true when
  // the walk came back to `start` (closed loop).
  auto walk = [&](uint32_t start) {
    out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
    out.types.push_back(lines.types[start / 2]);
    emit(start);
    uint32_t cur = start;
    bool closed = false;
    for (;;) {
      const uint32_t other = cur ^ 1u;
      scratch.used[cur / 2] = 1;
      emit(other);
      const uint32_t next = scratch.partner[other];
      if (next == kNone) break;
      if (scratch.used[next / 2]) {
        closed = next == start;
        break;
      }
      cur = next;
    }
    out.closed.push_back(closed ? 1 : 0);
  };
  // Open strokes first (from free ends), then the remaining closed loops.
  for (uint32_t k = 0; k < nends; ++k)
    if (scratch.partner[k] == kNone && !scratch.used[k / 2]) walk(k);
  for (uint32_t s = 0; s < ns; ++s)
    if (!scratch.used[s]) walk(2 * s);
  if (!out.types.empty()) out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
}

}  // namespace lodline
