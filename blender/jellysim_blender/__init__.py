"""Jellysim for Blender (docs/blender.md): a "Jellysim" panel in the 3D viewport's sidebar (N) to
pick a scene and set what an animator changes, *Simulate* running the `jellysim` CLI in the
background (progress in Blender's progress bar and status text, *Cancel* stops it at a step boundary
keeping what it wrote), and an import of the result into the collection "Jellysim", replaced by the
next one."""
import os
import tempfile

import bpy

from . import cli, importer

bl_info = {
    "name": "Jellysim",
    "author": "jellysim",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Jellysim",
    "description": "Simulate a swimming jellyfish with the jellysim CLI and import it (Mesh Cache)",
    "category": "Animation",
}

_runs = {}  # the background run of each window manager (one at a time)


class JellysimPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    cli_path: bpy.props.StringProperty(
        name="jellysim CLI", subtype="FILE_PATH", default="",
        description="The jellysim program; empty: `jellysim` on PATH")

    def draw(self, context):
        self.layout.prop(self, "cli_path")


class JellysimSettings(bpy.types.PropertyGroup):
    """What an animator changes, mapped to scene keys (`jellysim scenes jellyfish` gives ranges)."""
    scene_source: bpy.props.EnumProperty(
        name="Scene", items=[("BUILTIN", "Built-in jellyfish", "The CLI's built-in scene (Fig. 8.21's 4 cm bell)"),
                             ("FILE", "Scene file", "A scene file (TOML), e.g. share/jellysim/scenes/*.toml")])
    scene_file: bpy.props.StringProperty(name="Scene file", subtype="FILE_PATH")
    frequency: bpy.props.FloatProperty(name="Frequency", description="jellyfish.frequency: contractions per second",
                                       default=0.7, min=0.05, max=5.0, unit="NONE")
    diameter: bpy.props.FloatProperty(name="Bell size", description="jellyfish.diameter: bell diameter (m)",
                                      default=0.04, min=0.005, max=0.1, precision=3, unit="LENGTH")
    tentacle_length: bpy.props.FloatProperty(name="Tentacle length",
                                             description="jellyfish.tentacle_length (m); 0: none",
                                             default=0.014, min=0.0, max=0.2, precision=3, unit="LENGTH")
    colour: bpy.props.FloatVectorProperty(name="Colour", subtype="COLOR", size=3, min=0.0, max=1.0,
                                          default=(0.78, 0.9, 1.0),
                                          description="The shared bell material's colour (Blender only)")
    duration: bpy.props.FloatProperty(name="Duration", description="Simulated seconds (--duration)",
                                      default=2.0, min=0.05, max=600.0, unit="TIME_ABSOLUTE")
    quality: bpy.props.EnumProperty(
        name="Quality", description="The fluid grid (tank.cells)",
        items=[("DRAFT", "Draft", "48 x 96 cells: seconds, a rough idea"),
               ("PREVIEW", "Preview", "96 x 192 cells (16 across the bell)"),
               ("MEDIUM", "Medium", "192 x 384 cells"),
               ("FINAL", "Final", "384 x 768 cells: the built-in grid, within 10 % of converged")],
        default="PREVIEW")
    seed: bpy.props.IntProperty(name="Seed", description="render.noise.seed: the individual's surface noise",
                                default=1, min=0, max=2147483647)
    output_dir: bpy.props.StringProperty(
        name="Output", subtype="DIR_PATH", default="//jellysim",
        description="Where the runs go (take_NNN each); // is the .blend's folder (a temporary one if unsaved)")

    def params(self):
        return {"frequency": self.frequency, "diameter": self.diameter, "tentacle_length": self.tentacle_length,
                "duration": self.duration, "quality": self.quality, "seed": self.seed,
                "scene_file": bpy.path.abspath(self.scene_file) if self.scene_source == "FILE" else ""}


def output_root(settings):
    path = settings.output_dir
    if path.startswith("//") and not bpy.data.filepath:
        return os.path.join(tempfile.gettempdir(), "jellysim", path[2:])
    return bpy.path.abspath(path)


def start_run(context):
    """Starts `jellysim run` for the panel's settings; returns the cli.Run."""
    settings = context.scene.jellysim
    prefs = context.preferences.addons[__package__].preferences
    cmd = cli.build_command(cli.find_cli(prefs.cli_path), settings.params(),
                            cli.next_take_dir(output_root(settings)))
    return cli.Run(cmd)


def finish_run(context, run):
    """Imports a run that ended done or interrupted (what was computed); reports a failure."""
    status = run.status or {"status": "failed", "message": "\n".join(run.other_output) or "no status"}
    if status["status"] == "failed":
        return False, f"jellysim failed: {status.get('message')}"
    out = status.get("out") or run.cmd[run.cmd.index("--out") + 1]
    importer.import_run(out, context, tuple(context.scene.jellysim.colour))
    return True, f"jellysim: {status['status']}, imported {out}"


class JELLYSIM_OT_simulate(bpy.types.Operator):
    """Run the jellysim CLI in the background and import the result"""
    bl_idname = "jellysim.simulate"
    bl_label = "Simulate"
    _timer = None

    def execute(self, context):
        # Non-modal (scripts, background Blender, the tests): waits for the run, then imports.
        try:
            run = start_run(context)
        except FileNotFoundError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        run.wait()
        ok, message = finish_run(context, run)
        self.report({"INFO"} if ok else {"ERROR"}, message)
        return {"FINISHED"} if ok else {"CANCELLED"}

    def invoke(self, context, event):
        wm = context.window_manager
        if wm.as_pointer() in _runs:
            self.report({"WARNING"}, "a simulation is running")
            return {"CANCELLED"}
        try:
            _runs[wm.as_pointer()] = start_run(context)
        except FileNotFoundError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self._timer = wm.event_timer_add(0.2, window=context.window)
        wm.progress_begin(0, 1000)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # Blender stays responsive
        wm = context.window_manager
        run = _runs[wm.as_pointer()]
        running = run.poll()
        wm.progress_update(int(1000 * run.overall_fraction()))
        context.workspace.status_text_set(run.status_text())
        for area in context.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()
        if running:
            return {"PASS_THROUGH"}
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        del _runs[wm.as_pointer()]
        ok, message = finish_run(context, run)
        self.report({"INFO"} if ok else {"ERROR"}, message)
        return {"FINISHED"} if ok else {"CANCELLED"}


class JELLYSIM_OT_cancel(bpy.types.Operator):
    """Stop the running simulation at its next step (SIGINT); what it computed is imported"""
    bl_idname = "jellysim.cancel"
    bl_label = "Cancel"

    def execute(self, context):
        run = _runs.get(context.window_manager.as_pointer())
        if run is not None:
            run.cancel()
        return {"FINISHED"}


class JELLYSIM_OT_import(bpy.types.Operator):
    """Import a jellysim run's folder (summary.json, caches/) into the collection "Jellysim\""""
    bl_idname = "jellysim.import_run"
    bl_label = "Import Run"
    directory: bpy.props.StringProperty(subtype="DIR_PATH")

    def execute(self, context):
        importer.import_run(bpy.path.abspath(self.directory), context, tuple(context.scene.jellysim.colour))
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


class JELLYSIM_PT_panel(bpy.types.Panel):
    bl_label = "Jellysim"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Jellysim"

    def draw(self, context):
        s = context.scene.jellysim
        layout = self.layout
        layout.prop(s, "scene_source")
        if s.scene_source == "FILE":
            layout.prop(s, "scene_file")
        col = layout.column(align=True)
        for name in ("frequency", "diameter", "tentacle_length", "duration", "quality", "seed"):
            col.prop(s, name)
        layout.prop(s, "colour")
        layout.prop(s, "output_dir")
        run = _runs.get(context.window_manager.as_pointer())
        if run is None:
            layout.operator("jellysim.simulate", icon="PLAY")
        else:
            layout.label(text=run.status_text())
            layout.operator("jellysim.cancel", icon="CANCEL")
        layout.operator("jellysim.import_run", icon="IMPORT")


classes = (JellysimPreferences, JellysimSettings, JELLYSIM_OT_simulate, JELLYSIM_OT_cancel, JELLYSIM_OT_import,
           JELLYSIM_PT_panel)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.jellysim = bpy.props.PointerProperty(type=JellysimSettings)


def unregister():
    del bpy.types.Scene.jellysim
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
