#!/usr/bin/env python3
"""lodline against the line renderers users would pick instead, side by side in one run:
Blender's Freestyle (a rendered frame with silhouettes, borders, creases and suggestive
contours) and Line Art (its re-evaluation after a camera move), headless, on the armadillo and
the 1.1M-face torus knot at lodline's default view, 1280x720; and lodline's frames from
tests/bench/detail_frame_bench (T = 16 px²: the full-detail frame and the detail-controlled
one) in the same run (docs/performance.md, "Against Freestyle and Line Art").

Needs Blender (Debian: apt-get install blender; 3.4 on Debian 12) and a Release build.
The Blender side is scripts/blender_lines.py; the meshes are converted to OBJ for its importer.

  scripts/blender_side_by_side.py [--build build] [--out DIR] [--blender blender]
                                  [--freestyle-knot]   (Freestyle on the 1.1M knot too: slow)
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
ap = argparse.ArgumentParser()
ap.add_argument("--build", default=os.path.join(root, "build"))
ap.add_argument("--out", default="/tmp/lodline-blender")
ap.add_argument("--blender", default="blender")
ap.add_argument("--freestyle-knot", action="store_true")
args = ap.parse_args()

blender = shutil.which(args.blender)
if not blender:
    sys.exit("blender_side_by_side.py: Blender not found (Debian: apt-get install blender)")
lodline = os.path.join(args.build, "lodline")
bench = os.path.join(args.build, "tests/bench/detail_frame_bench")
for exe in (lodline, bench):
    if not os.access(exe, os.X_OK):
        sys.exit(f"blender_side_by_side.py: {exe}: not built (Release build needed)")
armadillo = os.path.join(root, "data/meshes/armadillo.off")
if not os.path.exists(armadillo):
    sys.exit(f"blender_side_by_side.py: {armadillo}: missing (run scripts/setup.sh)")
os.makedirs(args.out, exist_ok=True)


def off_to_obj(src, dst):
    """The OFF file's vertices and faces as an OBJ (Blender has no OFF importer)."""
    with open(src) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    if not words or not words[0].startswith("OFF"):
        sys.exit(f"blender_side_by_side.py: {src}: not an OFF file")
    k = 1
    nv, nf = int(words[k]), int(words[k + 1])
    k += 3
    tmp = dst + ".tmp"
    with open(tmp, "w") as o:
        for _ in range(nv):
            o.write(f"v {words[k]} {words[k + 1]} {words[k + 2]}\n")
            k += 3
        for _ in range(nf):
            n = int(words[k])
            o.write("f " + " ".join(str(int(v) + 1) for v in words[k + 1:k + 1 + n]) + "\n")
            k += 1 + n
    os.replace(tmp, dst)


models = {"armadillo": armadillo, "knot1m": os.path.join(args.out, "knot1m.off")}
if not os.path.exists(models["knot1m"]):
    subprocess.run([lodline, "generate", "knot", "--resolution", "2900", "-o", models["knot1m"]], check=True,
                   stdout=subprocess.DEVNULL)
objs = {}
for name, off in models.items():
    objs[name] = os.path.join(args.out, name + ".obj")
    if not os.path.exists(objs[name]):
        off_to_obj(off, objs[name])


def run_blender(name, mode):
    out = os.path.join(args.out, f"{name}-{mode}.json")
    cmd = [blender, "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1", "-P",
           os.path.join(here, "blender_lines.py"), "--", objs[name], mode, "1280", "720", "35", "20", out]
    if mode == "freestyle":
        cmd.append(os.path.join(args.out, f"{name}-freestyle.png"))
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"blender_side_by_side.py: Blender failed on {name} ({mode}):\n{r.stdout[-2000:]}")
    with open(out) as f:
        return json.load(f)


results = {}
for name in models:
    results[name] = {"lineart": run_blender(name, "lineart")}
    if name == "armadillo" or args.freestyle_knot:
        results[name]["freestyle"] = run_blender(name, "freestyle")
    print(f"{name}: Blender done", file=sys.stderr)

bench_json = os.path.join(args.out, "detail_frame.json")
env = dict(os.environ, EGL_PLATFORM="surfaceless")
subprocess.run([bench, "--benchmark_filter=detail_frame/(armadillo.off|knot1m)/T:16/iterations",
                "--benchmark_format=json", f"--benchmark_out={bench_json}"], check=True, env=env,
               stdout=subprocess.DEVNULL)
with open(bench_json) as f:
    for b in json.load(f)["benchmarks"]:
        name = "armadillo" if "armadillo" in b["name"] else "knot1m"
        results[name]["lodline"] = b

print("| model | faces | Freestyle, warm frame (without Freestyle) | Line Art, per camera move | lodline full-detail frame "
      "| lodline controlled frame (its line work) | Freestyle / lodline full | Line Art / lodline controlled |")
print("|---|---|---|---|---|---|---|---|")
for name, r in results.items():
    ll = r["lodline"]
    work = ll["adapt_ms"] + ll["shape_ms"] + ll["lines_ms"]
    fs = r.get("freestyle")
    fs_cell = f"{fs['warm_s']:.2f} s ({fs['surface_s']:.2f} s)" if fs else "not run"
    fs_ratio = f"{1000 * fs['warm_s'] / ll['full_ms']:.0f}×" if fs else "—"
    la = r["lineart"]
    print(f"| {name} | {int(ll['model_faces']):,} | {fs_cell} | {1000 * la['move_s']:.0f} ms ({la['points']:,} points) "
          f"| {ll['full_ms']:.1f} ms | {ll['controlled_ms']:.1f} ms ({work:.1f} ms) | {fs_ratio} "
          f"| {1000 * la['move_s'] / ll['controlled_ms']:.1f}× |")
print(f"\nBlender {results['armadillo']['lineart']['blender']}; figures and renders in {args.out}")
