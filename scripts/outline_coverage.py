#!/usr/bin/env python3
"""Outline coverage (docs/visibility.md): the fraction of the exterior outline pixels of the
faces as drawn (the boundary of their coverage mask) that have a drawn line pixel within
2 px, and the gaps of 5 px or more, as `lodline render --stats` reports them ("outline").

Renders every mesh at every view, full detail and with detail control, and prints one
markdown table; with --outline both, also the interpolated contour alone (the outline
before the mesh's silhouette completes it).

  scripts/outline_coverage.py [--build build] [--size 1920x1080]
                              [--meshes cow.off,elephant.off] [--views 60,20,1.6;60,20,2.2;35,20,0]
                              [--modes full,T16] [--outline complete|contour|both] [--all]
--all renders every mesh of data/meshes at the default framing (35,20,0) instead.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--size", default="1920x1080")
ap.add_argument("--meshes", default="cow.off,elephant.off,elk.off,pig.off,triceratops.off")
ap.add_argument("--views", default="60,20,1.6;60,20,2.2;35,20,0")
ap.add_argument("--modes", default="full,T16")
ap.add_argument("--outline", default="complete", choices=["complete", "contour", "both"])
ap.add_argument("--all", action="store_true")
args = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.path.join(root, args.build, "lodline")
data = os.path.join(root, "data", "meshes")
if args.all:
    meshes = sorted(f for f in os.listdir(data) if f.endswith(".off"))
    views = ["35,20,0"]
else:
    meshes = [m for m in args.meshes.split(",") if m]
    views = [v for v in args.views.split(";") if v]
modes = [m for m in args.modes.split(",") if m]
outlines = ["complete", "contour"] if args.outline == "both" else [args.outline]

print("| mesh | view | mode | outline | coverage | gaps >= 5 px | largest gap px | outline px |")
print("|---|---|---|---|---:|---:|---:|---:|")
worst = 1.0
failed = []
with tempfile.TemporaryDirectory() as tmp:
    for mesh in meshes:
        for view in views:
            for mode in modes:
                for outline in outlines:
                    stats = os.path.join(tmp, "s.json")
                    cmd = [exe, "render", os.path.join(data, mesh), "--style", "lines", "--view", view,
                           "--size", args.size, "--outline", outline, "-o", os.path.join(tmp, "o.png"),
                           "--stats", stats]
                    if mode == "full":
                        cmd.append("--full-detail")
                    elif mode.startswith("T"):
                        cmd += ["--target-area", mode[1:]]
                    r = subprocess.run(cmd, capture_output=True, text=True)
                    if r.returncode != 0:
                        failed.append(f"{mesh} {view} {mode}: {r.stderr.strip()}")
                        continue
                    o = json.load(open(stats))["outline"]
                    if outline == "complete":
                        worst = min(worst, o["coverage"])
                    print(f"| {mesh} | {view} | {mode} | {outline} | {o['coverage']:.4f} | {o['gaps']} | "
                          f"{o['largest_gap_px']} | {o['pixels']} |", flush=True)
print(f"\nworst coverage (complete outline): {worst:.4f}")
for f in failed:
    print("not rendered:", f, file=sys.stderr)
