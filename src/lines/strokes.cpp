#include "lines/strokes.h"

#include <algorithm>

#include "core/result.h"

namespace lodline {

void StrokeSet::clear() {
  points.clear();
  alpha.clear();
  offsets.clear();
  kinds.clear();
  closed.clear();
}

namespace {
constexpr uint32_t kNone = 0xffffffffu;
[[maybe_unused]] constexpr uint64_t kEndMask = (uint64_t{1} << 30) - 1;  // most segment ends supported
}  // namespace

void chainStrokes(const LineSet& lines, StrokeSet& out, ChainScratch& scratch) {
  out.clear();
  const size_t ns = lines.segmentCount();
  const size_t nends = 2 * ns;
  LODLINE_ASSERT(nends <= kEndMask);
  // Partner ends: two ends join when they are the only two with their (type, point id).
  // Ids are small (edge, vertex or interior indices), so a table indexed by kind·(largest id
  // + 1) + id finds them in one pass; only the entries touched are reset afterwards. Kind
  // first: a frame's ends are mostly of two or three kinds, whose entries then lie in as many
  // blocks, where id first spread them one in kLineKindCount over the whole table.
  scratch.partner.assign(nends, kNone);
  uint32_t max_id = 0;
  for (uint32_t id : lines.point_ids) max_id = std::max(max_id, id);
  const size_t ids = static_cast<size_t>(max_id) + 1;
  const size_t table_size = ids * kLineKindCount;
  if (scratch.first_end.size() < table_size) {
    scratch.first_end.resize(table_size, kNone);
    scratch.end_count.resize(table_size, 0);
  }
  auto slot = [&](size_t k) {
    return static_cast<size_t>(lines.kinds[k / 2]) * ids + static_cast<size_t>(lines.point_ids[k]);
  };
  for (size_t k = 0; k < nends; ++k) {
    const size_t t = slot(k);
    uint8_t& n = scratch.end_count[t];
    if (n == 0) {
      scratch.first_end[t] = static_cast<uint32_t>(k);
    } else if (n == 1) {
      const uint32_t a = scratch.first_end[t], b = static_cast<uint32_t>(k);
      if (a / 2 != b / 2) {  // a degenerate segment joining a point to itself stays alone
        scratch.partner[a] = b;
        scratch.partner[b] = a;
      }
    } else if (n == 2) {  // a third end: a junction, nobody joins here
      const uint32_t a = scratch.first_end[t];
      const uint32_t b = scratch.partner[a];
      scratch.partner[a] = kNone;
      if (b != kNone) scratch.partner[b] = kNone;
    }
    if (n < 3) ++n;
  }
  for (size_t k = 0; k < nends; ++k) {
    const size_t t = slot(k);
    scratch.end_count[t] = 0;
    scratch.first_end[t] = kNone;
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
    out.kinds.push_back(lines.kinds[start / 2]);
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
  if (!out.kinds.empty()) out.offsets.push_back(static_cast<uint32_t>(out.points.size()));
}

}  // namespace lodline
