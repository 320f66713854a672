"""The docs' Python experiment (scripts/python_focus_experiment.py) runs end to end: a
numpy detail map, a sweep over its strength, the CSV, chart and strip it writes, and fewer
active faces as the periphery gets coarser."""
import csv
import os
import subprocess
import sys

SOURCE = os.environ.get("LODLINE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_focus_experiment_quick(tmp_path):
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"))
    subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "python_focus_experiment.py"),
                    os.path.join(SOURCE, "models", "knot.off"), str(tmp_path), "--quick"], check=True, env=env)
    rows = list(csv.DictReader(open(tmp_path / "focus.csv")))
    assert [float(r["strength"]) for r in rows] == [0, 4, 16]
    faces = [int(r["active_faces"]) for r in rows]
    assert faces[0] > faces[1] > faces[2], faces
    assert (tmp_path / "focus_chart.svg").read_text().count("<polyline") == 2
    assert (tmp_path / "focus_strip.png").stat().st_size > 1000
