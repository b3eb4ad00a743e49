"""Builds a jellysim run's outputs into Blender (docs/blender.md), without Blender's glTF importer
(Blender 3.4's fails with Debian's NumPy) and without its OBJ operator (its vertex order is ours to
keep for the point cache):

- per jellyfish, caches/jellyfish_N.obj (frame 0, metres, y up) as a mesh with a Mesh Cache
  modifier on caches/jellyfish_N.pc2: every frame's world positions, so the root motion is in the
  cache; faces keep their part (umbrella, tentacles) as material slots;
- one translucent bell material (Principled BSDF with transmission) shared by every jellyfish, one
  for the tentacles, one for the obstacles (caches/obstacles.obj/.pc2 when the scene has any);
- the marine snow (the .glb's "marine_snow" mesh at frame 0) as a point cloud with an instanced speck;
- the scene's frame rate and range from the .glb's asset extras, as the generated
  blender_import.py sets them: cache frame 0 plays at the scene's start frame.

Everything lives in the collection "Jellysim", which the next import removes first.
"""
import json
import math
import os
import struct

import bpy

COLLECTION = "Jellysim"


def read_obj(path):
    """(vertices, faces, face_parts, part_names, uvs, face_uvs) of jellysim's OBJ: `v`, `vt`, `f`
    (1-based, v//vn or v/vt/vn) and `usemtl` parts, in the file's vertex order (the point cache's);
    face_uvs holds each face's vt indices (0-based) or None."""
    vertices, faces, parts, names, uvs, face_uvs = [], [], [], [], [], []
    part = 0
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                _, x, y, z = line.split()[:4]
                vertices.append((float(x), float(y), float(z)))
            elif line.startswith("vt "):
                _, u, v = line.split()[:3]
                uvs.append((float(u), float(v)))
            elif line.startswith("f "):
                corners = [t.split("/") for t in line.split()[1:]]
                faces.append(tuple(int(c[0]) - 1 for c in corners))
                face_uvs.append(tuple(int(c[1]) - 1 for c in corners) if all(len(c) > 1 and c[1] for c in corners) else None)
                parts.append(part)
            elif line.startswith("usemtl "):
                name = line.split(None, 1)[1].strip()
                if name not in names:
                    names.append(name)
                part = names.index(name)
    return vertices, faces, parts, names, uvs, face_uvs


def read_glb_json(path):
    """The JSON chunk and the binary chunk of a .glb."""
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + length])
    binary = b""
    at = 20 + length
    if at + 8 <= len(data):
        blen = struct.unpack_from("<I", data, at)[0]
        binary = data[at + 8:at + 8 + blen]
    return doc, binary


def glb_timing(doc):
    """(frames per second, frame count) from the asset extras (as blender_import.py reads them)."""
    extras = doc.get("asset", {}).get("extras", {})
    return float(extras.get("frames_per_second", 30.0)), int(extras.get("frame_count", 1))


def accessor_vec3(doc, binary, index, width=3):
    """A VEC3 (or `width`-wide) accessor's values as floats (float, or normalized short/byte as
    jellysim writes)."""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    fmt, size, scale = {5126: ("f", 4, 1.0), 5122: ("h", 2, 32767.0), 5120: ("b", 1, 127.0)}[acc["componentType"]]
    if not acc.get("normalized"):
        scale = 1.0
    stride = view.get("byteStride", width * size)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    out = []
    for k in range(acc["count"]):
        out.append(tuple(c / scale for c in struct.unpack_from("<%d%s" % (width, fmt), binary, start + k * stride)))
    return out


def glb_look(doc):
    """The .glb's materials by name: (rgba, roughness, transmission, ior)."""
    look = {}
    for m in doc.get("materials", []):
        pbr, ext = m.get("pbrMetallicRoughness", {}), m.get("extensions", {})
        look[m.get("name")] = (pbr.get("baseColorFactor", [0.8, 0.8, 0.8, 1.0]), pbr.get("roughnessFactor", 0.5),
                               ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0),
                               ext.get("KHR_materials_ior", {}).get("ior", 1.5))
    return look


def add_film_camera(doc, binary, coll, parent, scene):
    """The renderer's camera from the .glb (node "camera"): its view angle, the frames' size, and a
    key per frame when it moves; the scene looks through it. None when the file has none."""
    index = next((i for i, n in enumerate(doc.get("nodes", [])) if "camera" in n), None)
    if index is None:
        return None
    node, spec = doc["nodes"][index], doc["cameras"][doc["nodes"][index]["camera"]]
    data = bpy.data.cameras.new("jellysim_camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = spec["perspective"]["yfov"]
    data.clip_start, data.clip_end = spec["perspective"]["znear"], spec["perspective"]["zfar"]
    cam = bpy.data.objects.new("jellysim_camera", data)
    coll.objects.link(cam)
    cam.parent = parent  # the files' y up; the parent turns it to Blender's z up
    cam.rotation_mode = "QUATERNION"
    tracks = {"translation": [node["translation"]], "rotation": [node["rotation"]]}
    for channel in doc.get("animations", [{}])[0].get("channels", []) if doc.get("animations") else []:
        if channel["target"]["node"] == index:
            sampler = doc["animations"][0]["samplers"][channel["sampler"]]
            path = channel["target"]["path"]
            tracks[path] = accessor_vec3(doc, binary, sampler["output"], 3 if path == "translation" else 4)
    for k, (t, q) in enumerate(zip(tracks["translation"], tracks["rotation"])):
        cam.location = t
        cam.rotation_quaternion = (q[3], q[0], q[1], q[2])
        if len(tracks["translation"]) > 1:
            cam.keyframe_insert("location", frame=scene.frame_start + k)
            cam.keyframe_insert("rotation_quaternion", frame=scene.frame_start + k)
    size = spec.get("extras", {})
    if size.get("width_px") and size.get("height_px"):
        scene.render.resolution_x, scene.render.resolution_y = size["width_px"], size["height_px"]
        scene.render.resolution_percentage = 100
    scene.camera = cam
    return cam


def marine_snow_points(glb_path, specks):
    """The specks' centres at frame 0 (y up, metres), from the .glb's marine_snow mesh: its node's
    translation and its mesh node's scale, each speck's vertices averaged."""
    if not os.path.exists(glb_path) or specks <= 0:
        return []
    doc, binary = read_glb_json(glb_path)
    nodes = doc["nodes"]
    top = next((n for n in nodes if n.get("name") == "marine_snow"), None)
    if top is None:
        return []
    child = nodes[top["children"][0]]
    offset = top.get("translation", [0.0, 0.0, 0.0])
    scale = child.get("scale", [1.0, 1.0, 1.0])
    positions = accessor_vec3(doc, binary, doc["meshes"][child["mesh"]]["primitives"][0]["attributes"]["POSITION"])
    per = max(1, len(positions) // specks)
    points = []
    for s in range(len(positions) // per):
        group = positions[s * per:(s + 1) * per]
        points.append(tuple(offset[i] + scale[i] * sum(p[i] for p in group) / per for i in range(3)))
    return points


def remove_previous():
    """Removes the collection "Jellysim" and everything in it (meshes, materials of ours)."""
    coll = bpy.data.collections.get(COLLECTION)
    if coll is None:
        return
    meshes = set()
    for obj in list(coll.all_objects):
        if obj.type == "MESH":
            meshes.add(obj.data)
        bpy.data.objects.remove(obj, do_unlink=True)
    for child in list(coll.children_recursive):
        bpy.data.collections.remove(child)
    bpy.data.collections.remove(coll)
    for mesh in meshes:
        if mesh.users == 0:
            bpy.data.meshes.remove(mesh)


def principled(name, colour, alpha, transmission, roughness, ior=1.34):
    """A Principled BSDF material (reused when it exists: one shared bell material)."""
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (*colour[:3], 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior  # 1.34: water-filled gel in water would be near 1; a visible rim
    bsdf.inputs["Alpha"].default_value = alpha
    mat.blend_method = "BLEND" if alpha < 1.0 else "OPAQUE"
    mat.shadow_method = "HASHED" if alpha < 1.0 else "OPAQUE"
    mat.use_backface_culling = False
    mat.diffuse_color = (*colour[:3], alpha)  # the viewport's solid colour
    return mat


def materials(colour, look=None):
    """The add-on's materials: the bell in the panel's colour; opacity, transmission, roughness and
    IOR of the bell and the tentacles' colour from the run's .glb (`look`, glb_look) when it has them."""
    if look and "umbrella" in look and "tentacles" in look:
        bell, tentacles = look["umbrella"], look["tentacles"]
        return {
            "umbrella": principled("jellysim_bell", colour, bell[0][3], bell[2], bell[1], bell[3]),
            "tentacles": principled("jellysim_tentacles", tentacles[0], tentacles[0][3], tentacles[2], tentacles[1]),
            "obstacles": principled("jellysim_obstacles", (0.35, 0.32, 0.28), 1.0, 0.0, 0.8),
            "snow": principled("jellysim_snow", (0.85, 0.92, 0.95), 1.0, 0.0, 0.6),
        }
    return {
        "umbrella": principled("jellysim_bell", colour, 0.75, 0.7, 0.2),
        "tentacles": principled("jellysim_tentacles", [min(1.0, 0.5 + 0.5 * c) for c in colour[:3]], 0.85, 0.5, 0.4),
        "obstacles": principled("jellysim_obstacles", (0.35, 0.32, 0.28), 1.0, 0.0, 0.8),
        "snow": principled("jellysim_snow", (0.85, 0.92, 0.95), 1.0, 0.0, 0.6),
    }


def cached_mesh(name, obj_path, pc2_path, coll, parent, mats, start_frame):
    """The rest mesh with a Mesh Cache modifier on the PC2 file: cache frame 0 at `start_frame`."""
    vertices, faces, parts, names, uvs, face_uvs = read_obj(obj_path)
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    if uvs and any(face_uvs):  # the OBJ's vt (u around the axis or tube, v along the profile)
        flat = []
        for face, corners in zip(faces, face_uvs):
            for c in corners or [None] * len(face):
                flat.extend(uvs[c] if c is not None else (0.0, 0.0))
        mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", flat)
    for part in names:
        mesh.materials.append(mats.get(part, mats["umbrella"]))
    mesh.polygons.foreach_set("material_index", parts)
    mesh.polygons.foreach_set("use_smooth", [True] * len(faces))
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    coll.objects.link(obj)
    obj.parent = parent
    mod = obj.modifiers.new("jellysim cache", "MESH_CACHE")
    mod.cache_format = "PC2"
    mod.filepath = pc2_path
    mod.time_mode = "FRAME"
    mod.play_mode = "SCENE"
    mod.frame_start = start_frame
    mod.frame_scale = 1.0
    # The file holds the OBJ's own axes (y up); the parent turns the whole set to Blender's z up.
    mod.forward_axis = "POS_Y"
    mod.up_axis = "POS_Z"
    return obj


def add_marine_snow(points, coll, parent, mats, size):
    """A point cloud (a mesh of vertices) instancing one small speck at each point."""
    if not points:
        return None
    mesh = bpy.data.meshes.new("marine_snow")
    mesh.from_pydata(points, [], [])
    cloud = bpy.data.objects.new("marine_snow", mesh)
    coll.objects.link(cloud)
    cloud.parent = parent
    cloud.instance_type = "VERTS"
    speck_mesh = bpy.data.meshes.new("marine_snow_speck")
    r = 0.5 * size
    speck_mesh.from_pydata([(r, 0, 0), (-r, 0, 0), (0, r, 0), (0, -r, 0), (0, 0, r), (0, 0, -r)], [],
                           [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
    speck_mesh.materials.append(mats["snow"])
    speck = bpy.data.objects.new("marine_snow_speck", speck_mesh)
    coll.objects.link(speck)
    speck.parent = cloud
    return cloud


def set_scene_timing(scene, fps, frames):
    """The scene's frame rate (fps / fps_base) and range: `frames` frames from its start frame."""
    scene.render.fps = max(1, round(fps))
    scene.render.fps_base = scene.render.fps / fps
    scene.frame_end = scene.frame_start + frames - 1


def import_run(out_dir, context, colour=(0.78, 0.9, 1.0)):
    """Replaces the collection "Jellysim" with the run in `out_dir`; returns the collection."""
    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    glb = os.path.join(out_dir, "jellyfish.glb")
    doc, binary = read_glb_json(glb) if os.path.exists(glb) else ({}, b"")
    fps, frames = glb_timing(doc) if doc else (30.0, 1)
    remove_previous()
    scene = context.scene
    coll = bpy.data.collections.new(COLLECTION)
    scene.collection.children.link(coll)
    root = bpy.data.objects.new("jellysim_root", None)  # y up (the files) -> z up (Blender)
    root.rotation_euler = (math.pi / 2, 0.0, 0.0)
    coll.objects.link(root)
    root["jellysim_out"] = out_dir
    set_scene_timing(scene, fps, frames)
    mats = materials(colour, glb_look(doc))
    if doc:
        add_film_camera(doc, binary, coll, root, scene)
    caches = os.path.join(out_dir, "caches")
    names = sorted(f[:-4] for f in os.listdir(caches) if f.endswith(".obj")) if os.path.isdir(caches) else []
    for name in names:
        pc2 = os.path.join(caches, name + ".pc2")
        if os.path.exists(pc2):
            obj = cached_mesh(name, os.path.join(caches, name + ".obj"), pc2, coll, root, mats, scene.frame_start)
            if name == "obstacles":
                obj.data.materials[0] = mats["obstacles"]
    specks = int(summary.get("animation", {}).get("marine_snow_specks", 0) or 0)
    snow_size = float(summary.get("config", {}).get("render", {}).get("snow_size", 3e-4))
    add_marine_snow(marine_snow_points(glb, specks), coll, root, mats, snow_size)
    return coll
