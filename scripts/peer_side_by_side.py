#!/usr/bin/env python3
"""lodline's curvature and per-view line stages against rtsc's, side by side in one run
(docs/performance.md, "Against rtsc"). The peer is a small driver around trimesh2 and the
per-view code of rtsc (Rusinkiewicz & DeCarlo's real-time suggestive contours), built
separately (GPL, not part of lodline) and given with --peer; it is called as

    PEER MESH REPS VIEWS

and prints `curv median X ms` (need_normals + need_curvatures + need_dcurv on a fresh mesh,
point areas included) and `perview median Y ms/view` (n.v, kr and the suggestive test per
vertex, then contours where kr > 0 and suggestive contours, threshold 0.01/fs^2, fade
0.03/fs^2, back faces culled, over the orbit of tests/bench/lines_bench).

lodline's counterparts, one thread, on each mesh as stored and as lodline orders a
full-detail mesh when it loads it (core/mesh_order.h; the "ordered" rows):
  curvature + derivatives, fresh   BM_ShapeFresh threads:1 (new cache: arrays, corner areas,
                                   normals, curvature, derivatives, as rtsc's driver); in the
                                   ordered rows plus the reorder (BM_OrderForLocality)
  the same and the adjacency       BM_ShapeFullWithAdjacency threads:1 (vertex rings and edges
                                   too, which the line stages need: a drawing's first frame)
  curvature + derivatives, kept    BM_ShapeFull derivs:1 threads:1 (adjacency kept: what a
                                   frame pays when every vertex moved)
  contours + suggestive per view   BM_ContoursSuggestive

Each run times the peer and then lodline on each mesh, so the two share the machine's
state; the table gives each run's ratio (peer ms / lodline ms: above 1, lodline is faster)
and their median.

  scripts/peer_side_by_side.py --peer PATH [--build build] [--runs 3] [--meshes a.off,...]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

ap = argparse.ArgumentParser()
ap.add_argument("--peer", required=True, help="the rtsc driver (PEER MESH REPS VIEWS)")
ap.add_argument("--build", default="build")
ap.add_argument("--runs", type=int, default=3)
ap.add_argument("--meshes", default="armadillo.off,bunny00.off,refined_elephant.off")
ap.add_argument("--data", default="data/meshes")
ap.add_argument("--reps", type=int, default=5, help="peer curvature repetitions")
ap.add_argument("--views", type=int, default=100, help="peer views per repetition")
args = ap.parse_args()

meshes = args.meshes.split(",")
# Indices of the meshes in tests/bench/shape_bench.cpp (kMeshes) and lines_bench.cpp
# (kPeerMeshes), as stored and ordered.
shape_index = {"armadillo.off": 0, "bunny00.off": 1, "refined_elephant.off": 2}
shape_ordered = {"armadillo.off": 4, "bunny00.off": 5, "refined_elephant.off": 6}
lines_index = {"armadillo.off": 0, "bunny00.off": 1, "refined_elephant.off": 2}
lines_ordered = {"armadillo.off": 3, "bunny00.off": 4, "refined_elephant.off": 5}
for m in meshes:
    if m not in shape_index:
        sys.exit(f"peer_side_by_side.py: {m}: not among the benchmarks' meshes {sorted(shape_index)}")
    if not os.path.exists(os.path.join(args.data, m)):
        sys.exit(f"peer_side_by_side.py: {os.path.join(args.data, m)}: missing (run scripts/setup.sh)")
for exe in ("shape_bench", "lines_bench"):
    if not os.access(os.path.join(args.build, "tests/bench", exe), os.X_OK):
        sys.exit(f"peer_side_by_side.py: {args.build}/tests/bench/{exe}: not built")


def peer(mesh):
    out = subprocess.run([args.peer, os.path.join(args.data, mesh), str(args.reps), str(args.views)],
                         capture_output=True, text=True, check=True).stdout
    curv = re.search(r"curv median ([0-9.]+) ms", out)
    view = re.search(r"perview median ([0-9.]+) ms/view", out)
    if not curv or not view:
        sys.exit(f"peer_side_by_side.py: unexpected peer output:\n{out}")
    return float(curv.group(1)), float(view.group(1))


def bench(exe, pattern):
    out = subprocess.run([os.path.join(args.build, "tests/bench", exe), f"--benchmark_filter={pattern}",
                          "--benchmark_format=json", "--benchmark_min_time=0.5"],
                         capture_output=True, text=True, check=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
    if len(runs) != 1:
        sys.exit(f"peer_side_by_side.py: {exe} {pattern}: {len(runs)} results")
    b = runs[0]
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["real_time"] * scale


rows = {m: [] for m in meshes}
ordered_rows = {m: [] for m in meshes}
for run in range(args.runs):
    for m in meshes:
        p_curv, p_view = peer(m)
        s = shape_index[m]
        fresh = bench("shape_bench", f"^BM_ShapeFresh/mesh:{s}/threads:1$")
        with_adj = bench("shape_bench", f"^BM_ShapeFullWithAdjacency/mesh:{s}/threads:1$")
        kept = bench("shape_bench", f"^BM_ShapeFull/mesh:{s}/derivs:1/threads:1$")
        view = bench("lines_bench", f"^BM_ContoursSuggestive/mesh:{lines_index[m]}$")
        rows[m].append((p_curv, fresh, with_adj, kept, p_view, view))
        o = shape_ordered[m]
        reorder = bench("shape_bench", f"^BM_OrderForLocality/mesh:{s}$")
        o_fresh = bench("shape_bench", f"^BM_ShapeFresh/mesh:{o}/threads:1$") + reorder
        o_adj = bench("shape_bench", f"^BM_ShapeFullWithAdjacency/mesh:{o}/threads:1$") + reorder
        o_kept = bench("shape_bench", f"^BM_ShapeFull/mesh:{o}/derivs:1/threads:1$")
        o_view = bench("lines_bench", f"^BM_ContoursSuggestive/mesh:{lines_ordered[m]}$")
        ordered_rows[m].append((p_curv, o_fresh, o_adj, o_kept, p_view, o_view))
        print(f"run {run + 1} {m}: curvature peer {p_curv:.2f} ms, lodline fresh {fresh:.2f} / with adjacency "
              f"{with_adj:.2f} / kept {kept:.2f} ms, ordered: fresh {o_fresh:.2f} (of it reorder {reorder:.2f}) / "
              f"with adjacency {o_adj:.2f} / kept {o_kept:.2f} ms; "
              f"per view peer {p_view:.3f} ms, lodline {view:.3f} ms, ordered {o_view:.3f} ms", file=sys.stderr)

print("| mesh | curvature + derivatives: rtsc / lodline fresh / with adjacency / kept (ms) "
      "| speed-up fresh, with adjacency, kept | contours + suggestive per view: rtsc / lodline (ms) | speed-up |")
print("|---|---|---|---|---|")
for m, r in [(m, rows[m]) for m in meshes] + [(m + " (ordered)", ordered_rows[m]) for m in meshes]:
    med = lambda k: statistics.median(x[k] for x in r)
    ratio = lambda peer_k, k: [x[peer_k] / x[k] for x in r]
    runs = lambda v: ", ".join(f"{x:.2f}" for x in v)
    speed = lambda v: f"{statistics.median(v):.2f}× ({runs(v)})"
    print(f"| {m} | {med(0):.1f} / {med(1):.1f} / {med(2):.1f} / {med(3):.1f} "
          f"| {speed(ratio(0, 1))}, {speed(ratio(0, 2))}, {speed(ratio(0, 3))} "
          f"| {med(4):.2f} / {med(5):.2f} | {speed(ratio(4, 5))} |")
