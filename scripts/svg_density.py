#!/usr/bin/env python3
"""SVG stroke density (docs/visibility.md, "Vector output"): renders meshes at their default
view with --svg and reports, per mesh, the strokes' total length (the Bézier paths sampled
densely, lines and polylines as they are), the coordinate pairs written (one for M and L,
three for C) and
the length per pair; with rsvg-convert installed, also how the rasterised SVG matches the
PNG (line pixels within 1 px of a line pixel of the other, both ways).

  scripts/svg_density.py [--build build] [--size 1280x720] [--meshes camel.off,bunny00.off,armadillo.off]
                         [--extra "--style lines"]
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--size", default="1280x720")
ap.add_argument("--meshes", default="camel.off,bunny00.off,armadillo.off")
ap.add_argument("--extra", default="--style lines", help="options added to every render (one string)")
args = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.path.join(root, args.build, "lodline")
env = dict(os.environ, EGL_PLATFORM="surfaceless")
NUM = re.compile(r"-?\d+(?:\.\d+)?")


def bezier(p, t):
    s = 1 - t
    return tuple(s ** 3 * p[0][k] + 3 * s * s * t * p[1][k] + 3 * s * t * t * p[2][k] + t ** 3 * p[3][k] for k in (0, 1))


def measure(svg):
    length, pairs = 0.0, 0
    for d in re.findall(r' d="([^"]*)"', svg):
        cur = None
        for cmd, body in re.findall(r"([MLCz])([^MLCz]*)", d):
            nums = [float(x) for x in NUM.findall(body)]
            pts = list(zip(nums[0::2], nums[1::2]))
            pairs += len(pts)
            if cmd == "M":
                cur = pts[0]
            elif cmd == "L":
                length += math.dist(cur, pts[0])
                cur = pts[0]
            elif cmd == "C":
                ctrl = [cur] + pts[:3]
                prev = cur
                for k in range(1, 33):
                    q = bezier(ctrl, k / 32)
                    length += math.dist(prev, q)
                    prev = q
                cur = pts[2]
    for pts_attr in re.findall(r' points="([^"]*)"', svg):
        nums = [float(x) for x in NUM.findall(pts_attr)]
        pts = list(zip(nums[0::2], nums[1::2]))
        pairs += len(pts)
        length += sum(math.dist(a, b) for a, b in zip(pts, pts[1:]))
    return length, pairs


def dark(pixels, w, h):
    return {(i % w, i // w) for i, v in enumerate(pixels) if v < 200}


def read_gray(path):
    """A PNG as grey levels over white (ffmpeg decodes it: scripts/setup.sh installs it)."""
    with open(path, "rb") as f:
        head = f.read(24)
    w, h = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    rgba = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgba", "-"],
                          capture_output=True, check=True).stdout
    grey = bytearray(w * h)
    for i in range(w * h):
        r, g, b, a = rgba[4 * i: 4 * i + 4]
        v = (299 * r + 587 * g + 114 * b) // 1000
        grey[i] = (a * v + (255 - a) * 255) // 255
    return w, h, bytes(grey)


def near(a, b):
    if not a:
        return 0.0
    hit = sum(1 for (x, y) in a if any((x + dx, y + dy) in b for dx in (-1, 0, 1) for dy in (-1, 0, 1)))
    return hit / len(a)


rsvg = shutil.which("rsvg-convert") and shutil.which("ffmpeg")
print("| mesh | strokes' length px | coordinate pairs | px per pair | SVG near PNG | PNG near SVG |")
print("|---|---:|---:|---:|---:|---:|")
with tempfile.TemporaryDirectory() as tmp:
    for mesh in args.meshes.split(","):
        path = mesh if os.path.exists(mesh) else os.path.join(root, "data", "meshes", mesh)
        png, svg = os.path.join(tmp, "l.png"), os.path.join(tmp, "l.svg")
        cmd = [exe, "render", path, "--size", args.size, "--msaa", "1", "-o", png, "--svg", svg] + args.extra.split()
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stderr))
        length, pairs = measure(open(svg).read())
        a = b = float("nan")
        if rsvg:
            raster = os.path.join(tmp, "s.png")
            subprocess.run(["rsvg-convert", svg, "-o", raster], check=True)
            w, h, sp = read_gray(raster)
            _, _, gp = read_gray(png)
            ds, dg = dark(sp, w, h), dark(gp, w, h)
            a, b = near(ds, dg), near(dg, ds)
        print("| %s | %.0f | %d | %.2f | %.4f | %.4f |" % (os.path.basename(mesh), length, pairs,
                                                          length / max(pairs, 1), a, b), flush=True)
