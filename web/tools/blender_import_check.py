# Imports a jellysim .glb into Blender and checks its morph-target animation arrived:
#   blender -b --factory-startup --python-exit-code 1 --python web/tools/blender_import_check.py -- FILE.glb FRAMES
# Exits non-zero (via an exception) when the mesh, its shape keys or the animation are missing.
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
path, frames = args[0], int(args[1])
bpy.ops.wm.read_factory_settings(use_empty=True)
# Debian's numpy lacks an alias the importer's default shading code uses (see environment notes).
bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH")
meshes = [o for o in bpy.data.objects if o.type == "MESH"]
assert meshes, "no mesh imported"
vertices = sum(len(o.data.vertices) for o in meshes)
for o in meshes:
    keys = o.data.shape_keys
    assert keys is not None, f"{o.name}: no shape keys"
    # Basis + one key per later frame.
    assert len(keys.key_blocks) == frames, f"{o.name}: {len(keys.key_blocks)} shape keys, expected {frames}"
    action = keys.animation_data.action if keys.animation_data else None
    assert action is not None and len(action.fcurves) == frames - 1, f"{o.name}: shape-key animation missing"
print(f"blender import ok: {len(meshes)} mesh objects, {vertices} vertices, {frames} frames, "
      f"scene frames {bpy.context.scene.frame_start}-{bpy.context.scene.frame_end}")
