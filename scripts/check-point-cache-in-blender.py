# Checks a point cache of `jellysim run` in Blender (not a dependency of jellysim; Debian's
# `blender` package): imports the rest mesh, adds a Mesh Cache modifier with its default axes
# reading the PC2 file, and compares every vertex at a few scene frames with the file's samples.
#   blender -b --factory-startup --python scripts/check-point-cache-in-blender.py -- \
#       out/caches/jellyfish_1.obj out/caches/jellyfish_1.pc2
# Prints "RESULT OK" when Blender's evaluated mesh is the cache's sample at every frame checked.
import struct
import sys

import bpy

obj_path, pc2_path = sys.argv[-2], sys.argv[-1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=obj_path)
objects = bpy.context.selected_objects
assert len(objects) == 1, f"the rest mesh imported as {len(objects)} objects"
ob = objects[0]
cache = ob.modifiers.new("jellysim", 'MESH_CACHE')
cache.cache_format = 'PC2'
cache.filepath = pc2_path

with open(pc2_path, 'rb') as f:
    data = f.read()
signature, version, points, start, rate, samples = struct.unpack('<12siiffi', data[:32])
assert signature == b'POINTCACHE2\0' and version == 1, "not a PC2 file"
assert points == len(ob.data.vertices), f"{points} cache points, {len(ob.data.vertices)} mesh vertices"

worst = 0.0
for frame in sorted({0, samples // 2, samples - 1}):
    bpy.context.scene.frame_set(frame)
    mesh = ob.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    for i, v in enumerate(mesh.vertices):
        offset = 32 + (frame * points + i) * 12
        expected = struct.unpack('<fff', data[offset:offset + 12])
        worst = max(worst, max(abs(a - b) for a, b in zip(v.co, expected)))
print(f"{points} points, {samples} samples; largest difference {worst:.3g} m")
print("RESULT", "OK" if worst < 1e-6 else "MISMATCH")
