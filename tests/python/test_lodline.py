"""The lodline Python module (docs/python.md): renders equal the CLI's, numpy inputs act as
their files do, captures yield their frames with metrics, memory stays flat, errors are
exceptions with lodline's message, and the GIL is released while drawing."""
import gc
import os
import resource
import subprocess
import threading
import time

import numpy as np
import pytest

import lodline

SOURCE = os.environ.get("LODLINE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BIN = os.environ.get("LODLINE_BIN", os.path.join(SOURCE, "build", "lodline"))
KNOT = os.path.join(SOURCE, "models", "knot.off")


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return str(tmp_path_factory.mktemp("pmcache"))


def sphere(n=24):
    """A UV sphere as numpy arrays (float64 vertices, int32 faces)."""
    V = [(0.0, 0.0, 1.0)]
    for i in range(1, n):
        th = np.pi * i / n
        for j in range(2 * n):
            ph = 2 * np.pi * j / (2 * n)
            V.append((np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)))
    V.append((0.0, 0.0, -1.0))
    F = []
    ring = lambda i, j: 1 + (i - 1) * 2 * n + (j % (2 * n))
    for j in range(2 * n):
        F.append((0, ring(1, j), ring(1, j + 1)))
    for i in range(1, n - 1):
        for j in range(2 * n):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            F.append((a, c, d))
            F.append((a, d, b))
    last = len(V) - 1
    for j in range(2 * n):
        F.append((last, ring(n - 1, j + 1), ring(n - 1, j)))
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int32)


def test_simplest_call_returns_image_and_stats(cache):
    f = lodline.render(KNOT, size=(160, 120), target_area=16, cache_dir=cache)
    assert f.image.shape == (120, 160, 4) and f.image.dtype == np.uint8
    assert f.depth.shape == (120, 160) and f.depth.dtype == np.float32
    assert f.stats["image"] == {"width": 160, "height": 120, "coverage_px": f.stats["image"]["coverage_px"]}
    assert 0 < f.stats["lod"]["active_faces"] < 69120
    assert f.stats["lod"]["target_area"] == 16
    # Lines were drawn: dark pixels on the white page, and strokes with kinds.
    assert (f.image[..., :3].min(axis=2) < 64).sum() > 100
    assert len(f.strokes) == len(f.stroke_kinds) > 0
    assert all(s.ndim == 2 and s.shape[1] == 2 for s in f.strokes)
    assert set(f.stroke_kinds) <= {"contour", "suggestive", "crease", "boundary", "intersection"}
    assert f.svg.startswith("<?xml") and "<svg" in f.svg
    # Depth: background 1, the model nearer.
    assert f.depth[0, 0] == 1.0 and f.depth.min() < 1.0


def test_render_equals_cli_png(cache, tmp_path):
    png, stats = tmp_path / "cli.png", tmp_path / "cli.json"
    args = dict(size=(200, 150), target_area=24, view=(30, 15, 3), style="lines")
    subprocess.run([BIN, "render", KNOT, "--size", "200x150", "--target-area", "24", "--view", "30,15,3",
                    "--style", "lines", "--cache-dir", cache, "-o", str(png), "--stats", str(stats)], check=True)
    f = lodline.Renderer().render(KNOT, cache_dir=cache, **args)
    cli = lodline.read_png(png)
    assert np.array_equal(cli, f.image)
    import json
    s = json.loads(stats.read_text())
    assert s["lod"]["active_faces"] == f.stats["lod"]["active_faces"]
    assert s["strokes"] == f.stats["strokes"] == len(f.strokes)


def test_numpy_mesh_renders_and_is_checked():
    V, F = sphere()
    m = lodline.Mesh(V, F)
    assert m.vertex_count == len(V) and m.face_count == len(F)
    f = lodline.Renderer().render(m, size=(128, 96), full_detail=True, style="lines")
    assert f.stats["faces_drawn"] == len(F)
    assert f.stats["model"]["faces"] == len(F)
    assert "contour" in f.stroke_kinds
    # float32 input gives the same mesh.
    assert np.allclose(lodline.Mesh(V.astype(np.float32), F).V, m.V)
    bad = V.copy()
    bad[3, 1] = np.nan
    with pytest.raises(lodline.UsageError, match="vertex 3 has a coordinate that is not finite"):
        lodline.Mesh(bad, F)
    with pytest.raises(lodline.UsageError, match="is not a vertex index"):
        lodline.Mesh(V, F + len(V))
    with pytest.raises(lodline.UsageError, match="N×3"):
        lodline.Mesh(V[:, :2], F)
    with pytest.raises(lodline.UsageError, match="integer"):
        lodline.Mesh(V, F.astype(np.float64))


def test_scene_built_in_python(cache):
    V, F = sphere(12)
    s = lodline.Scene()
    s.add(lodline.Mesh(V, F), name="ball")
    move = np.eye(4)
    move[0, 3] = 3.0
    s.add(KNOT, matrix=move, detail_factor=2.0, style={"lines": "contour"})
    assert len(s) == 2
    f = lodline.Renderer().render(s, size=(200, 100), cache_dir=cache)
    names = [o["name"] for o in f.stats["objects"]]
    assert names == ["ball", "knot"]
    assert set(np.unique(f.stroke_objects)) == {0, 1}
    assert f.stats["objects"][1]["detail_factor"] == 2.0


def look_at(eye, target, up):
    f = np.subtract(target, eye)
    f = f / np.linalg.norm(f)
    r = np.cross(f, up)
    r = r / np.linalg.norm(r)
    u = np.cross(r, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = r, u, -f
    m[:3, 3] = -m[:3, :3] @ np.asarray(eye, float)
    return m


def test_camera_as_pose_or_view_matrix(cache):
    eye, target = (0.5, 1.0, 4.0), (0.0, 0.0, 0.0)
    r = lodline.Renderer(reuse=False)
    by_pose = r.render(KNOT, size=(160, 120), cache_dir=cache, camera=dict(eye=eye, target=target, up=(0, 1, 0)))
    by_matrix = r.render(KNOT, size=(160, 120), cache_dir=cache, camera=look_at(eye, target, (0, 1, 0)))
    default = r.render(KNOT, size=(160, 120), cache_dir=cache)
    assert np.abs(by_pose.image.astype(int) - by_matrix.image.astype(int)).max() <= 1
    assert not np.array_equal(by_pose.image, default.image)
    with pytest.raises(lodline.UsageError, match="camera"):
        r.render(KNOT, camera=dict(eye=eye))


def test_numpy_detail_map_equals_png_map(cache, tmp_path):
    h, w = 120, 160
    grey = np.full((h, w), 255, dtype=np.uint8)
    grey[:, : w // 2] = 16  # left half: finer detail
    path = tmp_path / "map.png"
    lodline.write_png(path, grey)
    common = dict(size=(w, h), target_area=32, cache_dir=cache, view=(0, 0, 3))
    from_array = lodline.Renderer().render(KNOT, detail_map=grey, **common)
    from_file = lodline.Renderer().render(KNOT, detail_map=str(path), **common)
    plain = lodline.Renderer().render(KNOT, **common)
    assert from_array.stats["lod"]["active_faces"] == from_file.stats["lod"]["active_faces"]
    assert np.array_equal(from_array.image, from_file.image)
    assert from_array.stats["lod"]["active_faces"] != plain.stats["lod"]["active_faces"]
    # Float factors: all 1 is the same as no map.
    ones = lodline.Renderer().render(KNOT, detail_map=np.ones((h, w), np.float32), **common)
    assert ones.stats["lod"]["active_faces"] == plain.stats["lod"]["active_faces"]


def test_capture_iterator_yields_frames_with_metrics(cache):
    cap = lodline.capture(KNOT, path="orbit", duration=4, fps=30, size=(96, 72), style="lines", cache_dir=cache)
    assert len(cap) == 120
    frames = list(cap)
    assert len(frames) == 120
    assert [f.index for f in frames] == list(range(120))
    assert all(f.image.shape == (72, 96, 4) for f in frames)
    assert {"frame", "churn", "specks", "active_faces"} <= set(frames[5].metrics)
    assert frames[5].metrics["frame"] == 5
    assert any(f.metrics["churn"] > 0 for f in frames[1:])
    # A range renders the same frames as the whole path.
    part = list(lodline.capture(KNOT, path="orbit", duration=4, fps=30, size=(96, 72), style="lines",
                                cache_dir=cache, frames=(60, 63)))
    assert [f.index for f in part] == [60, 61, 62]
    assert np.array_equal(part[1].image, frames[61].image)
    assert part[1].metrics["churn"] == frames[61].metrics["churn"]


def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def test_memory_flat_over_1000_renders(cache):
    r = lodline.Renderer()
    views = [(a, 20, 3) for a in range(0, 360, 36)]
    for i in range(100):
        r.render(KNOT, size=(64, 48), view=views[i % 10], target_area=48, cache_dir=cache)
    before = rss_kib()
    for i in range(900):
        f = r.render(KNOT, size=(64, 48), view=views[i % 10], target_area=48, cache_dir=cache)
    after = rss_kib()
    assert f.image.shape == (48, 64, 4)
    assert after - before < 8 * 1024, f"RSS grew by {after - before} KiB over 900 renders"


def test_errors_are_exceptions_with_lodline_messages(tmp_path):
    missing = tmp_path / "missing.off"
    with pytest.raises(lodline.Error, match="missing.off: no such file"):
        lodline.render(missing)
    with pytest.raises(lodline.UsageError, match="unknown option 'no_such_option'"):
        lodline.render(KNOT, no_such_option=3)
    with pytest.raises(lodline.UsageError, match="--size"):
        lodline.render(KNOT, size="big")
    nan = tmp_path / "nan.off"
    nan.write_text("OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(lodline.Error, match="nan.off"):
        lodline.render(nan)
    assert issubclass(lodline.UsageError, lodline.Error)
    assert issubclass(lodline.Error, RuntimeError)


def test_gil_released_while_rendering(cache):
    r = lodline.Renderer()
    kw = dict(size=(640, 480), full_detail=True, cache_dir=cache)
    t0 = time.perf_counter()
    r.render(KNOT, **kw)
    one = time.perf_counter() - t0
    gaps = []
    done = threading.Event()

    def work():
        for _ in range(3):
            r.render(KNOT, view=(40, 20, 3), **kw)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    last = time.perf_counter()
    while not done.is_set():
        now = time.perf_counter()
        gaps.append(now - last)
        last = now
        time.sleep(0.001)
    t.join()
    # Were the GIL held while drawing, this loop would stall for whole renders.
    assert max(gaps) < 0.5 * one, f"longest stall {max(gaps):.3f} s against a render of {one:.3f} s"


def test_two_renderers_each_keep_their_context(cache):
    # Each renderer draws in its own GL context; dropping one leaves the other drawing the same
    # image (it used to end the shared EGL display and leave no context current: a black image).
    r1, r2 = lodline.Renderer(), lodline.Renderer()
    r1.render(KNOT, size=(64, 48), cache_dir=cache)
    before = r2.render(KNOT, size=(64, 48), cache_dir=cache).image
    del r1
    gc.collect()
    after = r2.render(KNOT, size=(64, 48), cache_dir=cache).image
    assert after.mean() > 100
    assert np.array_equal(after, before)


def test_ridge_estimator_is_an_option(cache):
    """Ridges and valleys from the per-face tensors or from fitted jets (docs/lines.md)."""
    kw = dict(size=(320, 240), lines="contour,ridge,valley", cache_dir=cache)
    fit = lodline.render(KNOT, ridge_estimator="fit", **kw)
    tensor = lodline.render(KNOT, ridge_estimator="tensor", **kw)
    assert fit.stats["lines"]["ridge"] > 0 and tensor.stats["lines"]["ridge"] > 0
    assert fit.stats["lines"]["contour"] == tensor.stats["lines"]["contour"]
    assert (fit.stats["lines"]["ridge"], fit.stats["lines"]["valley"]) != (
        tensor.stats["lines"]["ridge"], tensor.stats["lines"]["valley"])
    with pytest.raises(lodline.UsageError, match="--ridge-estimator"):
        lodline.render(KNOT, ridge_estimator="guess", **kw)
