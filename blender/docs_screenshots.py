"""The add-on's screenshots in docs/blender.md, in a real Blender window under Xvfb:
- `panel`: docs/images/blender_panel.png, the panel after a short Draft run (the simulate operator's
  non-modal core), the Tool and View tabs removed so that the Jellysim tab shows;
- `running`: docs/images/blender_running.png, the modal Simulate of a 4 s Preview run: Blender's
  timers keep running while the CLI works, the status bar's text mid-run, the import at the end.
  export BLENDER_USER_CONFIG=$(mktemp -d) BLENDER_USER_SCRIPTS=$(mktemp -d)
  blender -b --factory-startup --python-expr "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"
  xvfb-run -a -s "-screen 0 1280x720x24" blender --python blender/docs_screenshots.py -- \
      panel|running build/release/jellysim_blender.zip build/release/jellysim OUT.png
"""
import os
import sys
import tempfile
import time

import bpy

mode, zip_path, cli_path, out = sys.argv[sys.argv.index("--") + 1:]
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="jellysim_blender")
bpy.context.preferences.addons["jellysim_blender"].preferences.cli_path = cli_path
s = bpy.context.scene.jellysim
s.output_dir = os.path.join(tempfile.gettempdir(), "jellysim-screenshot-runs")
s.colour = (0.9, 0.55, 0.75)
import jellysim_blender  # noqa: E402  (installed above)

state = {"t0": time.time(), "shot": False}


def view_3d():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    return window, area, next(r for r in area.regions if r.type == "WINDOW")


def frame_the_jellyfish():
    bpy.context.scene.frame_set(4)
    window, area, region = view_3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.clip_start = 0.0005
    space.shading.type = "SOLID"
    space.shading.color_type = "MATERIAL"
    for o in bpy.data.objects:
        o.select_set(o.name == "jellyfish_1")
    bpy.context.view_layer.objects.active = bpy.data.objects["jellyfish_1"]
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.view3d.view_axis(type="FRONT")
        bpy.ops.view3d.view_selected()
    for o in bpy.data.objects:
        o.select_set(False)
    bpy.context.view_layer.objects.active = None  # no Item tab: the Jellysim tab shows


def shoot_and_quit():
    bpy.ops.screen.screenshot(filepath=out)
    print("screenshot", out)
    bpy.ops.wm.quit_blender()


def start_modal():
    window, area, region = view_3d()
    area.spaces.active.show_region_ui = True
    with bpy.context.temp_override(window=window, area=area, region=region):
        print("invoke:", bpy.ops.jellysim.simulate("INVOKE_DEFAULT"))


def watch_modal():
    runs = jellysim_blender._runs
    if runs and not state["shot"] and time.time() - state["t0"] > 3.5:
        run = next(iter(runs.values()))
        print("mid-run:", run.status_text(), run.overall_fraction())
        bpy.ops.screen.screenshot(filepath=out)
        state["shot"] = True
    if not runs and time.time() - state["t0"] > 3:
        scene = bpy.context.scene
        print("finished:", [o.name for o in bpy.data.collections["Jellysim"].objects], "frames",
              scene.frame_start, scene.frame_end)
        bpy.ops.wm.quit_blender()
        return None
    return 0.5


if mode == "panel":
    s.quality, s.duration = "DRAFT", 0.5
    bpy.ops.jellysim.simulate()
    # Only the Jellysim tab in the sidebar (3.4 has no API to pick a tab): the Tool and View panels go.
    for cls in list(bpy.types.Panel.__subclasses__()):
        if getattr(cls, "bl_space_type", "") == "VIEW_3D" and getattr(cls, "bl_region_type", "") == "UI" \
                and getattr(cls, "bl_category", "Tool") in ("Tool", "View"):
            bpy.utils.unregister_class(cls)
    bpy.app.timers.register(frame_the_jellyfish, first_interval=1.0)
    bpy.app.timers.register(shoot_and_quit, first_interval=5.0)
else:
    s.quality, s.duration = "PREVIEW", 4.0
    bpy.app.timers.register(start_modal, first_interval=1.0)
    bpy.app.timers.register(watch_modal, first_interval=2.0)
