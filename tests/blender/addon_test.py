"""The Blender add-on in headless Blender (issue 38; tests/blender/addon_test.sh runs it):
installs the zip, simulates a very short run on a coarse grid through the Simulate operator's
non-modal core, checks the objects, the Mesh Cache modifier (its vertices are the cache's), the
frame range, the shared bell material, the marine snow; simulates again (the import is replaced,
not duplicated); cancels a longer run (SIGINT: "interrupted", what it wrote imports); renders one
small Cycles frame on the CPU and checks the jellyfish is in it.
  blender -b --factory-startup --python-exit-code 1 --python addon_test.py -- ZIP CLI WORKDIR [WIDTH SAMPLES]
"""
import math
import os
import struct
import sys
import time

import bpy
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
zip_path, cli_path, work = args[0], args[1], args[2]
width = int(args[3]) if len(args) > 3 else 96
samples = int(args[4]) if len(args) > 4 else 4
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def pc2_frame(path, frame):
    with open(path, "rb") as f:
        head = f.read(32)
        points = struct.unpack_from("<i", head, 16)[0]
        f.seek(32 + frame * points * 12)
        return [struct.unpack_from("<3f", f.read(12)) for _ in range(1)][0], points


# An empty scene: the factory start-up's 2 m cube would enclose the 4 cm bell (and the camera).
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)

# Install and enable the zip as a user would (Preferences > Add-ons > Install).
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="jellysim_blender")
prefs = bpy.context.preferences.addons["jellysim_blender"].preferences
prefs.cli_path = cli_path
scene = bpy.context.scene
s = scene.jellysim
s.quality = "DRAFT"
s.duration = 0.2
s.output_dir = os.path.join(work, "runs")
s.colour = (0.9, 0.55, 0.75)

t0 = time.time()
check(bpy.ops.jellysim.simulate() == {"FINISHED"}, "Simulate finished")
print(f"simulate + import: {time.time() - t0:.1f} s")
coll = bpy.data.collections.get("Jellysim")
check(coll is not None, "collection Jellysim")
jelly = bpy.data.objects.get("jellyfish_1")
check(jelly is not None and jelly.name in coll.objects, "jellyfish_1 in it")
mod = jelly.modifiers[0]
check(mod.type == "MESH_CACHE" and mod.cache_format == "PC2" and os.path.exists(mod.filepath),
      f"Mesh Cache modifier on {mod.filepath}")
frames = 7  # 0.2 s at 30 frames/s: frames 0..6
check(scene.frame_start == 1 and scene.frame_end == scene.frame_start + frames - 1,
      f"frame range {scene.frame_start}-{scene.frame_end} ({frames} frames)")
check(abs(scene.render.fps / scene.render.fps_base - 30.0) < 1e-6, "30 frames per second")
check(mod.frame_start == scene.frame_start, "cache frame 0 at the scene's start frame")

# The evaluated mesh's first vertex is the cache's, in the same (file) coordinates, at two frames.
for frame in (0, frames - 1):
    scene.frame_set(scene.frame_start + frame)
    evaluated = jelly.evaluated_get(bpy.context.evaluated_depsgraph_get())
    expected, points = pc2_frame(mod.filepath, frame)
    got = evaluated.data.vertices[0].co
    check(len(evaluated.data.vertices) == points and (got - Vector(expected)).length < 1e-6,
          f"frame {frame}: vertex 0 {tuple(got)} = cache {expected}")
bell = bpy.data.materials.get("jellysim_bell")
check(bell is not None and bell.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value < 0.5
      and bell.blend_method == "BLEND", "translucent bell material (Principled BSDF, alpha-blended as jellysim draws it)")
check(jelly.data.materials[0] == bell and len(jelly.data.materials) == 2, "bell and tentacle slots")
snow = bpy.data.objects.get("marine_snow")
check(snow is not None and len(snow.data.vertices) > 10 and snow.instance_type == "VERTS",
      f"marine snow: {len(snow.data.vertices) if snow else 0} instanced specks")

# Simulating again replaces the import: one collection, one jellyfish, one bell material.
check(bpy.ops.jellysim.simulate() == {"FINISHED"}, "Simulate again")
check(len([c for c in bpy.data.collections if c.name.startswith("Jellysim")]) == 1, "one Jellysim collection")
check(len([o for o in bpy.data.objects if o.name.startswith("jellyfish_1")]) == 1, "one jellyfish_1")
check(len([m for m in bpy.data.materials if m.name.startswith("jellysim_bell")]) == 1, "one bell material")
check(bpy.data.objects["jellyfish_1"].modifiers[0].filepath.find("take_002") >= 0, "the new take's cache")

# A scene file with obstacles (its rock outline is relative to the working directory: the source
# tree's root, where addon_test.sh starts Blender): their own cached mesh and stone material.
s.scene_source, s.scene_file = "FILE", os.path.abspath("scenes/obstacles.toml")
check(bpy.ops.jellysim.simulate() == {"FINISHED"}, "Simulate scenes/obstacles.toml")
obstacles = bpy.data.objects.get("obstacles")
check(obstacles is not None and obstacles.modifiers[0].type == "MESH_CACHE"
      and obstacles.data.materials[0].name == "jellysim_obstacles", "obstacles with their Mesh Cache and material")
s.scene_source = "BUILTIN"

# Cancel: SIGINT stops the CLI at a step boundary; it reports "interrupted" and what it wrote imports.
from jellysim_blender import cli, importer  # noqa: E402
params = s.params()
params["duration"] = 60.0
run = cli.Run(cli.build_command(cli_path, params, os.path.join(work, "cancelled")))
deadline = time.time() + 30
while run.progress is None and time.time() < deadline:
    run.poll()
    time.sleep(0.05)
run.cancel()
status = run.wait(30)
check(status is not None and status["status"] == "interrupted" and status["exit_code"] == 130,
      f"cancelled run: {status}")
importer.import_run(status["out"], bpy.context)
check(bpy.data.objects.get("jellyfish_1") is not None, "the cancelled run's frames import")
check(bpy.ops.jellysim.simulate() == {"FINISHED"}, "Simulate once more (for the picture)")

# A small Cycles frame on the CPU: camera on the bell, a light, a dark-blue world.
scene.frame_set(scene.frame_start + frames // 2)
jelly = bpy.data.objects["jellyfish_1"]
evaluated = jelly.evaluated_get(bpy.context.evaluated_depsgraph_get())
world_points = [jelly.matrix_world @ v.co for v in evaluated.data.vertices]
centre = sum(world_points, Vector()) / len(world_points)
size = max((p - centre).length for p in world_points)
cam_data = bpy.data.cameras.new("jellysim_test_camera")
cam_data.clip_start = 0.01 * size  # a 4 cm bell: Blender's default 0.1 m would cut it all
cam_data.clip_end = 1000 * size
cam = bpy.data.objects.new("jellysim_test_camera", cam_data)
scene.collection.objects.link(cam)
cam.location = centre + Vector((0.6, -2.2, 0.5)).normalized() * size * 3.2
cam.rotation_euler = (centre - cam.location).to_track_quat("-Z", "Y").to_euler()
scene.camera = cam

light = bpy.data.objects.new("jellysim_test_light", bpy.data.lights.new("jellysim_test_light", "SUN"))
light.rotation_euler = (math.radians(40), math.radians(20), 0)
light.data.energy = 5.0
scene.collection.objects.link(light)
scene.world = scene.world or bpy.data.worlds.new("World")
scene.world.use_nodes = True
background = (0.02, 0.12, 0.22)  # sea water
scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (*background, 1.0)
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.render.resolution_x = width
scene.render.resolution_y = width if width <= 96 else width * 3 // 4
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.render.filepath = os.path.join(work, "frame.png")
t0 = time.time()
bpy.ops.render.render(write_still=True)
print(f"render {scene.render.resolution_x}x{scene.render.resolution_y}, {samples} samples: {time.time() - t0:.1f} s")
image = bpy.data.images.load(scene.render.filepath)
px = list(image.pixels)
n = len(px) // 4
reference = [px[0], px[1], px[2]]  # a corner: the background
differing = sum(1 for k in range(n) if sum(abs(px[4 * k + c] - reference[c]) for c in range(3)) > 0.08)
check(differing > 0.03 * n, f"the jellyfish covers {100 * differing / n:.1f} % of the frame")
print("picture:", scene.render.filepath)
if failures:
    print("FAILED:", failures)
    sys.exit(1)
print("RESULT OK")
