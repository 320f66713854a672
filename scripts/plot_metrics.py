#!/usr/bin/env python3
"""Plots per-frame churn (motion-compensated and raw) and specks from `lodline capture
--metrics` CSVs into a PNG chart. Churn is shown as a centred moving mean over SMOOTH frames
(per-frame values of a few line pixels are mostly 0 or a spike).
Needs Debian's python3-matplotlib (only for making documentation charts).

  /usr/bin/python3 scripts/plot_metrics.py OUT.png TITLE [--smooth N] label=file.csv [label=file.csv ...]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

args = sys.argv[1:]
smooth = 9
if "--smooth" in args:
    i = args.index("--smooth")
    smooth = int(args[i + 1])
    del args[i:i + 2]
out, title, runs = args[0], args[1], args[2:]


def moving_mean(values, n):
    h = n // 2
    return [sum(values[max(0, i - h):i + h + 1]) / len(values[max(0, i - h):i + h + 1]) for i in range(len(values))]


fig, (ax1, ax0, ax2) = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True)
for run in runs:
    label, path = run.split("=", 1)
    rows = list(csv.DictReader(open(path)))[1:]  # frame 0 has no previous frame
    frames = [int(r["frame"]) for r in rows]
    line, = ax1.plot(frames, moving_mean([float(r["churn"]) for r in rows], smooth), label=label, linewidth=1.2)
    ax0.plot(frames, moving_mean([float(r["churn_raw"]) for r in rows], smooth), label=label, linewidth=1.2,
             color=line.get_color())
    ax2.plot(frames, [int(r["specks"]) for r in rows], label=label, linewidth=1.2, color=line.get_color())
ax1.set_ylabel("churn, motion-compensated\n(mean of %d frames)" % smooth)
ax0.set_ylabel("churn_raw\n(mean of %d frames)" % smooth)
ax0.set_yscale("log")
ax2.set_ylabel("specks (strokes < 3 px)")
ax2.set_xlabel("frame (30 fps)")
ax1.set_title(title)
ax1.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=90)
