"""Checks the modal Simulate in a real Blender window (under Xvfb): invoke, Blender's timers keep
running while the CLI works (the status bar's text mid-run is screenshotted to
docs/images/blender_running.png), the import when it ends.
  export BLENDER_USER_CONFIG=$(mktemp -d) BLENDER_USER_SCRIPTS=$(mktemp -d)
  blender -b --factory-startup --python-expr "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"
  xvfb-run -a -s "-screen 0 1280x720x24" blender --python blender/modal_check.py -- \
      build/release/jellysim_blender.zip build/release/jellysim docs/images/blender_running.png
"""
import os
import sys
import tempfile
import time

import bpy
args = sys.argv[sys.argv.index("--") + 1:]
zip_path, cli_path, out = args
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj, do_unlink=True)
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="jellysim_blender")
bpy.context.preferences.addons["jellysim_blender"].preferences.cli_path = cli_path
s = bpy.context.scene.jellysim
s.quality = "PREVIEW"; s.duration = 4.0; s.output_dir = os.path.join(tempfile.gettempdir(), "wt38-modal-runs")
import jellysim_blender
state = {"t0": time.time(), "shot": False}
def start():
    w = bpy.context.window_manager.windows[0]
    area = next(a for a in w.screen.areas if a.type == "VIEW_3D")
    area.spaces.active.show_region_ui = True
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=w, area=area, region=region):
        print("invoke:", bpy.ops.jellysim.simulate("INVOKE_DEFAULT"))
    return None
def watch():
    runs = jellysim_blender._runs
    if runs and not state["shot"] and time.time() - state["t0"] > 3.5:
        r = next(iter(runs.values()))
        print("mid-run:", r.status_text(), r.overall_fraction())
        bpy.ops.screen.screenshot(filepath=out)
        state["shot"] = True
    if not runs and time.time() - state["t0"] > 3:
        print("finished; collection:", bpy.data.collections.get("Jellysim"), "objects:", [o.name for o in bpy.data.objects])
        print("frames", bpy.context.scene.frame_start, bpy.context.scene.frame_end)
        bpy.ops.wm.quit_blender()
        return None
    if time.time() - state["t0"] > 150:
        print("TIMEOUT"); bpy.ops.wm.quit_blender(); return None
    return 0.5
bpy.app.timers.register(start, first_interval=1.0)
bpy.app.timers.register(watch, first_interval=2.0)
