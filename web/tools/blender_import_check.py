# Imports a jellysim .glb into Blender and checks its morph-target animation arrived:
#   blender -b --factory-startup --python-exit-code 1 --python web/tools/blender_import_check.py -- FILE.glb TARGETS
# Exits non-zero (via an exception) when the mesh, its shape keys or the animation are missing.
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
path, targets = args[0], int(args[1])
bpy.ops.wm.read_factory_settings(use_empty=True)
# Debian's numpy lacks an alias the importer's default shading code uses (see environment notes).
bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH")
meshes = [o for o in bpy.data.objects if o.type == "MESH"]
assert meshes, "no mesh imported"
vertices = sum(len(o.data.vertices) for o in meshes)
moving = 0
for o in meshes:
    keys = o.data.shape_keys
    assert keys is not None, f"{o.name}: no shape keys"
    # Basis + one key per morph target (every render.glb_every-th frame and the last).
    assert len(keys.key_blocks) == targets + 1, f"{o.name}: {len(keys.key_blocks)} shape keys, expected {targets + 1}"
    action = keys.animation_data.action if keys.animation_data else None
    assert action is not None and len(action.fcurves) == targets, f"{o.name}: shape-key animation missing"
    root = o.parent
    moving += 1 if root is not None and root.animation_data and root.animation_data.action else 0
print(f"blender import ok: {len(meshes)} mesh objects, {vertices} vertices, {targets} morph targets each, "
      f"{moving} with root motion; scene frames {bpy.context.scene.frame_start}-{bpy.context.scene.frame_end} "
      f"at {bpy.context.scene.render.fps} fps")
