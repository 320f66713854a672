"""Runs inside Blender (headless) for scripts/blender_side_by_side.py: times Freestyle or Line
Art on one mesh at lodline's default view, and writes the figures as JSON.

    blender -b --factory-startup -noaudio --python-exit-code 1 -P scripts/blender_lines.py -- \
        MESH.obj freestyle|lineart WIDTH HEIGHT AZIMUTH ELEVATION OUT.json [OUT.png]

The view is lodline's `--view AZ,EL` with the default framing: a 35° vertical field of view,
the camera 1.08 bounding radii / sin(17.5°) from the centre of the bounding box (lodline is
Y-up; Blender's OBJ importer maps its -Z forward, Y up to Blender's Z up).

- freestyle: Cycles on the CPU with one sample and no denoising (the surface is not what is
  timed), Freestyle line set of silhouettes, borders, creases and suggestive contours, visible
  lines only, face smoothness on (needed for suggestive contours). Renders twice: `cold_s` is
  the first render, `warm_s` the second; then once without Freestyle, `surface_s`.
- lineart: a Grease Pencil object with a Line Art modifier over the scene (contours, creases,
  borders; Line Art has no suggestive contours). `first_s` is the first evaluation, `move_s` the
  median of 5 re-evaluations after a 0.5° step of the camera about the model (what a camera
  move costs), `points` the points of the strokes it made.
"""
import json
import math
import statistics
import sys
import time

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:]
mesh_path, mode = argv[0], argv[1]
width, height = int(argv[2]), int(argv[3])
az, el = math.radians(float(argv[4])), math.radians(float(argv[5]))
out_json = argv[6]
out_png = argv[7] if len(argv) > 7 else None
if mode not in ("freestyle", "lineart"):
    sys.exit(f"blender_lines.py: mode must be freestyle or lineart, got {mode}")

bpy.ops.wm.read_factory_settings(use_empty=True)
t0 = time.perf_counter()
bpy.ops.wm.obj_import(filepath=mesh_path)
import_s = time.perf_counter() - t0
ob = bpy.context.selected_objects[0]
mesh = ob.data
mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
mesh.update()
scene = bpy.context.scene

corners = [ob.matrix_world @ Vector(c) for c in ob.bound_box]
lo = Vector([min(c[i] for c in corners) for i in range(3)])
hi = Vector([max(c[i] for c in corners) for i in range(3)])
center, radius = (lo + hi) / 2, (hi - lo).length / 2
fov = math.radians(35.0)
dist = 1.08 * radius / math.sin(fov / 2)


def place(camera, azimuth):
    # lodline's orbit direction (cos el sin az, sin el, cos el cos az), Y-up, in Blender's axes.
    c = math.cos(el)
    d = Vector((c * math.sin(azimuth), -c * math.cos(azimuth), math.sin(el)))
    camera.location = center + dist * d
    camera.rotation_euler = (center - camera.location).to_track_quat("-Z", "Y").to_euler()


cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.lens_unit = "FOV"
cam_data.angle = fov
cam_data.clip_start = dist - 1.5 * radius if dist > 1.5 * radius else 1e-3 * dist
cam_data.clip_end = dist + 1.5 * radius
cam = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(cam)
scene.camera = cam
place(cam, az)
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
scene.collection.objects.link(sun)
sun.rotation_euler = cam.rotation_euler

scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
result = {"mode": mode, "mesh": mesh_path, "faces": len(mesh.polygons), "width": width, "height": height,
          "import_s": import_s, "blender": bpy.app.version_string}

if mode == "freestyle":
    scene.render.engine = "CYCLES"
    scene.world = bpy.data.worlds.new("white")  # a white background, so outlines show in the PNG
    scene.world.color = (1.0, 1.0, 1.0)
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.render.use_freestyle = True
    scene.render.line_thickness_mode = "ABSOLUTE"
    scene.render.line_thickness = 1.0
    layer = scene.view_layers[0]
    layer.use_freestyle = True
    fs = layer.freestyle_settings
    fs.mode = "EDITOR"
    fs.use_smoothness = True
    fs.use_culling = True
    lineset = fs.linesets[0] if len(fs.linesets) else fs.linesets.new("lines")
    if lineset.linestyle is None:
        lineset.linestyle = bpy.data.linestyles.new("lines")
    lineset.select_by_visibility = True
    lineset.visibility = "VISIBLE"
    lineset.select_by_edge_types = True
    lineset.select_silhouette = True
    lineset.select_border = True
    lineset.select_crease = True
    lineset.select_suggestive_contour = True
    times = []
    for _ in range(2):
        t0 = time.perf_counter()
        bpy.ops.render.render(write_still=False)
        times.append(time.perf_counter() - t0)
    result["cold_s"], result["warm_s"] = times
    if out_png:
        bpy.data.images["Render Result"].save_render(filepath=out_png)
    scene.render.use_freestyle = False  # the same frame without lines: the surface's share
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    result["surface_s"] = time.perf_counter() - t0
else:
    gp_data = bpy.data.grease_pencils.new("lineart")
    gp = bpy.data.objects.new("lineart", gp_data)
    scene.collection.objects.link(gp)
    gp_layer = gp_data.layers.new("lines", set_active=True)
    gp_layer.frames.new(scene.frame_current)
    material = bpy.data.materials.new("lines")
    bpy.data.materials.create_gpencil_data(material)
    gp_data.materials.append(material)
    mod = gp.grease_pencil_modifiers.new("lineart", "GP_LINEART")
    mod.source_type = "SCENE"
    mod.target_layer = "lines"
    mod.target_material = material
    mod.use_contour = mod.use_crease = mod.use_edge_mark = True
    layer = bpy.context.view_layer
    t0 = time.perf_counter()
    layer.update()
    result["first_s"] = time.perf_counter() - t0
    moves = []
    for k in range(1, 6):
        place(cam, az + math.radians(0.5 * k))
        t0 = time.perf_counter()
        layer.update()
        moves.append(time.perf_counter() - t0)
    result["move_s"] = statistics.median(moves)
    result["moves_s"] = moves
    evaluated = gp.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    result["points"] = sum(len(s.points) for l in evaluated.layers for f in l.frames for s in f.strokes)

with open(out_json, "w") as f:
    json.dump(result, f, indent=1)
print("blender_lines.py:", json.dumps(result))
