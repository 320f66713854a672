#!/usr/bin/env python3
"""Writes models/lifebuoy.obj: a torus in eight alternating red and white bands, two
materials named with OBJ `usemtl`, the example of material lines (docs/lines.md).

    scripts/make_lifebuoy.py [OUT.obj]
"""
import math
import sys

R, r = 1.0, 0.32          # ring and tube radii
MAJOR, MINOR = 96, 32     # segments around the ring and around the tube
BANDS = 8

out = sys.argv[1] if len(sys.argv) > 1 else "models/lifebuoy.obj"
lines = ["# lifebuoy: a torus in %d alternating bands (materials red, white); scripts/make_lifebuoy.py" % BANDS,
         "mtllib lifebuoy.mtl"]
for i in range(MAJOR):
    a = 2 * math.pi * i / MAJOR
    for j in range(MINOR):
        b = 2 * math.pi * j / MINOR
        rho = R + r * math.cos(b)
        lines.append("v %.6f %.6f %.6f" % (rho * math.cos(a), r * math.sin(b), rho * math.sin(a)))
faces = {0: [], 1: []}
for i in range(MAJOR):
    band = (i * BANDS // MAJOR) % 2
    for j in range(MINOR):
        v00 = i * MINOR + j
        v01 = i * MINOR + (j + 1) % MINOR
        v10 = ((i + 1) % MAJOR) * MINOR + j
        v11 = ((i + 1) % MAJOR) * MINOR + (j + 1) % MINOR
        # counter-clockwise seen from outside
        faces[band].append((v00, v01, v11))
        faces[band].append((v00, v11, v10))
for band, name in ((0, "red"), (1, "white")):
    lines.append("usemtl " + name)
    lines.extend("f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in faces[band])
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
