#!/usr/bin/env python3
"""A detail-map experiment driven from Python (docs/python.md).

The detail map is computed in numpy: the factor on the target area T grows with the image
distance from a focus point, f(d) = 1 + s * (d / d_max)^2, so the focus keeps T while the
periphery gets coarser by up to 1 + s. The sweep renders the model for several strengths s
and plots active faces and specks against s (an SVG chart written here, no plotting library
needed), and writes the frames of the weakest, middle and strongest maps side by side as one
PNG, the focus marked.

    PYTHONPATH=build/python python3 scripts/python_focus_experiment.py MODEL OUT_DIR [--quick]
"""
import argparse
import os
import sys

import numpy as np

import lodline


def focus_map(width, height, focus, strength):
    """H×W float32 factors on T: 1 at the focus, 1 + strength in the farthest corner."""
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float32)
    d = np.hypot(xs - focus[0], ys - focus[1])
    return (1.0 + strength * (d / d.max()) ** 2).astype(np.float32)


def svg_chart(path, xs, series, xlabel):
    """A small line chart: one polyline per (name, values, colour), each scaled to its own max."""
    w, h, m = 560, 300, 50
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="DejaVu Sans" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<line x1="{m}" y1="{h - m}" x2="{w - m}" y2="{h - m}" stroke="black"/>',
           f'<text x="{w / 2}" y="{h - 12}" text-anchor="middle">{xlabel}</text>']
    x0, x1 = min(xs), max(xs)
    for k, (name, values, colour) in enumerate(series):
        top = max(values) or 1
        pts = []
        for x, v in zip(xs, values):
            px = m + (x - x0) / ((x1 - x0) or 1) * (w - 2 * m)
            py = h - m - v / top * (h - 2 * m)
            pts.append(f"{px:.1f},{py:.1f}")
            out.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="3" fill="{colour}"/>')
        out.append(f'<polyline points="{" ".join(pts)}" fill="none" stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{m + 8}" y="{20 + 16 * k}" fill="{colour}">{name} (max {top:g})</text>')
    for x in xs:
        px = m + (x - x0) / ((x1 - x0) or 1) * (w - 2 * m)
        out.append(f'<text x="{px:.1f}" y="{h - m + 16}" text-anchor="middle">{x:g}</text>')
    out.append("</svg>")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("model")
    ap.add_argument("out_dir")
    ap.add_argument("--quick", action="store_true", help="small images and three strengths (the test)")
    a = ap.parse_args()
    os.makedirs(a.out_dir, exist_ok=True)
    width, height = (240, 160) if a.quick else (640, 400)
    strengths = [0, 4, 16] if a.quick else [0, 1, 2, 4, 8, 16, 32]
    focus = (0.42 * width, 0.32 * height)  # on the back of the default view of the armadillo
    # A fresh scene per render (reuse=False): each row is what `lodline render` gives for that map.
    renderer = lodline.Renderer(reuse=False)
    rows = []
    strip = []
    for s in strengths:
        f = renderer.render(a.model, size=(width, height), style="lines", target_area=8,
                            detail_map=focus_map(width, height, focus, s))
        rows.append((s, f.stats["lod"]["active_faces"], f.stats["specks"], f.stats["strokes"]))
        if s in (strengths[0], strengths[len(strengths) // 2], strengths[-1]):
            image = f.image.copy()
            fx, fy = int(focus[0]), int(focus[1])  # the focus as a small red cross
            image[fy - 1:fy + 2, fx - 8:fx + 9] = (220, 40, 40, 255)
            image[fy - 8:fy + 9, fx - 1:fx + 2] = (220, 40, 40, 255)
            strip.append(image)
        print(f"strength {s:>4g}: {rows[-1][1]:>7} active faces, {rows[-1][2]:>4} specks, {rows[-1][3]:>5} strokes")
    with open(os.path.join(a.out_dir, "focus.csv"), "w") as out:
        out.write("strength,active_faces,specks,strokes\n")
        for r in rows:
            out.write(",".join(str(x) for x in r) + "\n")
    svg_chart(os.path.join(a.out_dir, "focus_chart.svg"), [r[0] for r in rows],
              [("active faces", [r[1] for r in rows], "#1f5fa8"), ("specks", [r[2] for r in rows], "#c0392b")],
              "strength s of the detail map (T x 1 + s (d/d_max)^2)")
    lodline.write_png(os.path.join(a.out_dir, "focus_strip.png"), np.concatenate(strip, axis=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
