#!/usr/bin/env python3
"""Measures detail control (docs/detail-control.md): band fraction, scaling of visible
triangles with image area / T over a 16x zoom-out, independence of model size, for the
CGAL demo meshes and generated 1M-triangle models. Uses only `lodline render --stats`.

  scripts/measure_detail.py [--build build] [--out out/detail]
Prints markdown tables to stdout.
"""
import argparse
import json
import os
import subprocess
import sys

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--out", default="out/detail")
args = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.path.join(root, args.build, "lodline")
out = os.path.join(root, args.out)
os.makedirs(out, exist_ok=True)
cache = os.path.join(out, "cache")
env = dict(os.environ, EGL_PLATFORM="surfaceless")


def run(cmd):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stdout + r.stderr))
    return r


def render(model, name, extra):
    stats = os.path.join(out, name + ".json")
    run([exe, "render", model, "-o", os.path.join(out, name + ".png"), "--stats", stats,
         "--cache-dir", cache] + extra)
    with open(stats) as f:
        return json.load(f)


def generated(kind, res, name):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        run([exe, "generate", kind, "-o", path, "--resolution", str(res)])
    return path


data = os.path.join(root, "data", "meshes")
models = [(os.path.join(data, m), m) for m in ("bunny00.off", "armadillo.off", "refined_elephant.off")]
models.append((os.path.join(root, "models", "knot.off"), "knot.off (69k)"))
knot690 = generated("knot", 2280, "knot690k.off")
knot1m = generated("knot", 2900, "knot1m.off")
models.append((knot1m, "knot1m.off (1.1M)"))

print("## Band fraction after convergence (1280x720, default view, T = 16 px²)\n")
print("| model | faces | active faces | visible faces | band fraction | coverage px | visible/(coverage/T) |")
print("|---|---|---|---|---|---|---|")
for path, name in models:
    j = render(path, "band-" + os.path.basename(path), [])
    lod = j["lod"]
    cov = j["image"]["coverage_px"]
    print("| %s | %d | %d | %d | %.3f | %d | %.2f |" % (name, j["model"]["faces"], lod["active_faces"],
          lod["visible_faces"], lod["band_fraction"], cov, lod["visible_faces"] / (cov / 16.0)))

print("\n## Zoom-out: visible triangles track image area / T (armadillo and knot1m)\n")
print("| model | distance (radii) | coverage px | visible faces | visible/(coverage/T) | band | full-detail faces |")
print("|---|---|---|---|---|---|---|")
for path, name in [(os.path.join(data, "armadillo.off"), "armadillo"), (knot1m, "knot1m")]:
    for d in (2.5, 5, 10, 20, 40):
        j = render(path, "zoom-%s-%g" % (name, d), ["--view", "35,20,%g" % d])
        lod = j["lod"]
        cov = max(1, j["image"]["coverage_px"])
        print("| %s | %g | %d | %d | %.2f | %.3f | %d |" % (name, d, cov, lod["visible_faces"],
              lod["visible_faces"] / (cov / 16.0), lod["band_fraction"], j["model"]["faces"]))

print("\n## Model size x10 at the same view (knot 69k vs 690k vs 1.1M faces)\n")
print("| model | faces | active faces | visible faces | band |")
print("|---|---|---|---|---|")
for path, name in [(os.path.join(root, "models", "knot.off"), "knot 69k"), (knot690, "knot 690k"),
                   (knot1m, "knot 1.1M")]:
    j = render(path, "size-" + os.path.basename(path), ["--view", "35,20,3"])
    lod = j["lod"]
    print("| %s | %d | %d | %d | %.3f |" % (name, j["model"]["faces"], lod["active_faces"],
          lod["visible_faces"], lod["band_fraction"]))
