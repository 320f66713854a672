#!/usr/bin/env python3
"""Stroke-id persistence of a `lodline capture --svg DIR/` sequence (docs/capture.md): for
each pair of consecutive frames, the fraction of the later frame's stroke length (and of
its strokes) whose id the earlier frame already had.

  scripts/stroke_id_persistence.py DIR
"""
import glob
import math
import re
import sys

if len(sys.argv) != 2:
    sys.exit(__doc__)


def strokes(path):
    out = {}
    for sid, d in re.findall(r'<path id="s(\d+)"[^>]* d="([^"]*)"', open(path).read()):
        pts = [tuple(map(float, p)) for p in re.findall(r"(-?\d+(?:\.\d+)?),(-?\d+(?:\.\d+)?)", d)]
        out[int(sid)] = sum(math.dist(a, b) for a, b in zip(pts, pts[1:]))  # control polygon: close enough
    return out


frames = [strokes(f) for f in sorted(glob.glob(sys.argv[1].rstrip("/") + "/frame_*.svg"))]
if len(frames) < 2:
    sys.exit("need at least two frame_*.svg files in " + sys.argv[1])
by_length, by_count = [], []
for a, b in zip(frames, frames[1:]):
    total = sum(b.values())
    by_length.append(sum(l for i, l in b.items() if i in a) / total if total else 1.0)
    by_count.append(sum(1 for i in b if i in a) / len(b) if b else 1.0)
print("frames %d, strokes per frame %.1f" % (len(frames), sum(len(f) for f in frames) / len(frames)))
print("stroke length keeping its id: mean %.3f, min %.3f" % (sum(by_length) / len(by_length), min(by_length)))
print("strokes keeping their id: mean %.3f" % (sum(by_count) / len(by_count)))
