#!/usr/bin/env python3
"""Plots per-frame churn (motion-compensated and raw) and specks from `lodline capture
--metrics` CSVs into a PNG chart.
Needs Debian's python3-matplotlib (only for making documentation charts).

  /usr/bin/python3 scripts/plot_metrics.py OUT.png TITLE label=file.csv [label=file.csv ...]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, title, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
fig, (ax1, ax0, ax2) = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True)
for run in runs:
    label, path = run.split("=", 1)
    rows = list(csv.DictReader(open(path)))
    frames = [int(r["frame"]) for r in rows]
    line, = ax1.plot(frames[1:], [max(float(r["churn"]), 1e-5) for r in rows][1:], label=label, linewidth=1)
    ax0.plot(frames[1:], [max(float(r["churn_raw"]), 1e-5) for r in rows][1:], label=label, linewidth=1,
             color=line.get_color())
    ax2.plot(frames, [int(r["specks"]) for r in rows], label=label, linewidth=1)
ax1.set_ylabel("churn (motion-compensated)")
ax1.set_yscale("log")
ax0.set_ylabel("churn_raw")
ax0.set_yscale("log")
ax2.set_ylabel("specks (strokes < 3 px)")
ax2.set_xlabel("frame (30 fps)")
ax1.set_title(title)
ax1.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=90)
