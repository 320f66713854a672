#!/usr/bin/env python3
"""Plots per-frame churn and specks from `lodline capture --metrics` CSVs into a PNG chart.
Needs Debian's python3-matplotlib (only for making documentation charts).

  /usr/bin/python3 scripts/plot_metrics.py OUT.png TITLE label=file.csv [label=file.csv ...]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, title, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
for run in runs:
    label, path = run.split("=", 1)
    rows = list(csv.DictReader(open(path)))
    frames = [int(r["frame"]) for r in rows]
    ax1.plot(frames[1:], [float(r["churn"]) for r in rows][1:], label=label, linewidth=1)
    ax2.plot(frames, [int(r["specks"]) for r in rows], label=label, linewidth=1)
ax1.set_ylabel("churn")
ax1.set_yscale("log")
ax2.set_ylabel("specks (strokes < 3 px)")
ax2.set_xlabel("frame (30 fps)")
ax1.set_title(title)
ax1.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=90)
