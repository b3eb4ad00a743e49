"""docs/images/blender_panel.png: the add-on's panel after a short Draft run, in a real Blender window
under Xvfb (a fresh user configuration whose preferences turn the splash off first):
  export BLENDER_USER_CONFIG=$(mktemp -d) BLENDER_USER_SCRIPTS=$(mktemp -d)
  blender -b --factory-startup --python-expr "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"
  xvfb-run -a -s "-screen 0 1280x720x24" blender --python blender/panel_screenshot.py -- \
      build/release/jellysim_blender.zip build/release/jellysim docs/images/blender_panel.png
"""
import os
import sys
import tempfile

import bpy
args = sys.argv[sys.argv.index("--") + 1:]
zip_path, cli_path, out = args
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="jellysim_blender")
bpy.context.preferences.addons["jellysim_blender"].preferences.cli_path = cli_path
s = bpy.context.scene.jellysim
s.quality = "DRAFT"; s.duration = 0.5; s.output_dir = os.path.join(tempfile.gettempdir(), "jellysim-screenshot-runs"); s.colour = (0.9, 0.55, 0.75)
bpy.ops.jellysim.simulate()
# Only the Jellysim tab in the sidebar (3.4 has no API to pick a tab): the Tool and View panels go.
for cls in list(bpy.types.Panel.__subclasses__()):
    if getattr(cls, "bl_space_type", "") == "VIEW_3D" and getattr(cls, "bl_region_type", "") == "UI" \
            and getattr(cls, "bl_category", "Tool") in ("Tool", "View", "Item"):
        try:
            bpy.utils.unregister_class(cls)
        except Exception:
            pass
def setup():
    bpy.context.scene.frame_set(4)
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                space = area.spaces.active
                space.show_region_ui = True
                space.clip_start = 0.0005
                space.shading.type = "SOLID"
                space.shading.color_type = "MATERIAL"
                region = next(r for r in area.regions if r.type == "WINDOW")
                for o in bpy.data.objects:
                    o.select_set(o.name == "jellyfish_1")
                bpy.context.view_layer.objects.active = bpy.data.objects["jellyfish_1"]
                with bpy.context.temp_override(window=window, area=area, region=region):
                    bpy.ops.view3d.view_axis(type="FRONT")
                    bpy.ops.view3d.view_selected()
                for o in bpy.data.objects:
                    o.select_set(False)
                bpy.context.view_layer.objects.active = None  # no Item tab: the Jellysim tab shows
    return None
def shoot():
    bpy.ops.screen.screenshot(filepath=out)
    print("screenshot", out)
    bpy.ops.wm.quit_blender()
bpy.app.timers.register(setup, first_interval=1.0)
bpy.app.timers.register(shoot, first_interval=5.0)
