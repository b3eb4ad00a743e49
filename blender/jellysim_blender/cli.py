"""The jellysim CLI as a background process (no bpy here, so it is testable outside Blender).

`jellysim run --progress json` writes one JSON object per line on stderr (README, "Using it"):
stage lines ({"stage", "fraction", "eta_seconds", ...}) and a last status line ({"status":
"done"|"failed"|"interrupted", "exit_code", "out", "message"}). A reader thread queues them; the
add-on's modal operator drains the queue on a timer, so Blender never waits on the pipe.
"""
import json
import os
import queue
import shutil
import signal
import subprocess
import threading

# Quality presets: the fluid grid (tank.cells) of the built-in 24 x 48 cm tank. FINAL is the built-in
# grid (64 cells across the 4 cm bell, README); the others are coarser previews of the same animal.
QUALITY_GRIDS = {
    "DRAFT": (48, 96),
    "PREVIEW": (96, 192),
    "MEDIUM": (192, 384),
    "FINAL": (384, 768),
}


def find_cli(preferred=""):
    """The jellysim program: the path set in the add-on's preferences, else `jellysim` on PATH."""
    if preferred:
        path = os.path.abspath(os.path.expanduser(preferred))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise FileNotFoundError(f"the jellysim CLI set in the add-on's preferences is not a program: {path}")
    found = shutil.which("jellysim")
    if not found:
        raise FileNotFoundError("no `jellysim` on PATH: set its path in the add-on's preferences")
    return found


def scene_overrides(params):
    """The --set assignments for the animator's parameters (the real scene keys, `jellysim scenes
    jellyfish`): frequency, bell size (diameter), tentacle length, quality (grid), seed. Colour is
    a material setting in Blender, not a simulation input."""
    nx, ny = QUALITY_GRIDS[params["quality"]]
    sets = [
        f"jellyfish.frequency={params['frequency']!r}",
        f"jellyfish.diameter={params['diameter']!r}",
        f"jellyfish.tentacle_length={params['tentacle_length']!r}",
        f"tank.cells=[{nx},{ny}]",
        f"render.noise.seed={int(params['seed'])}",
        # What the import needs (caches, .glb for the frame rate and the marine snow); no video,
        # no PNG frames, no HTML viewer: Blender renders.
        "render.pc2=true", "render.glb=true", "render.video=false", "render.png_frames=false",
        "render.viewer=false",
    ]
    return sets


def build_command(cli, params, out_dir):
    """`jellysim run [SCENE] --out DIR --duration S --set ... --progress json`."""
    cmd = [cli, "run"]
    if params.get("scene_file"):
        cmd.append(params["scene_file"])
    cmd += ["--out", out_dir, "--duration", repr(float(params["duration"])), "--progress", "json"]
    for s in scene_overrides(params):
        cmd += ["--set", s]
    return cmd


def next_take_dir(root):
    """root/take_NNN, the first that does not exist: each simulation writes its own folder, so the
    previous import keeps reading its caches until it is replaced."""
    os.makedirs(root, exist_ok=True)
    k = 1
    while os.path.exists(os.path.join(root, f"take_{k:03d}")):
        k += 1
    return os.path.join(root, f"take_{k:03d}")


class Run:
    """One `jellysim run` in the background: its progress lines, its status, Cancel."""

    def __init__(self, cmd):
        self.cmd = cmd
        self.lines = queue.Queue()
        self.progress = None  # the last stage line
        self.status = None  # the status line, once it came
        self.other_output = []  # stderr lines that are not JSON (the CLI's human-readable error)
        self.proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                     bufsize=1)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for line in self.proc.stderr:
            line = line.strip()
            if not line:
                continue
            try:
                self.lines.put(json.loads(line))
            except ValueError:
                self.other_output.append(line)
        self.proc.stderr.close()

    def poll(self):
        """Takes the lines that came; returns True while the process runs."""
        while True:
            try:
                line = self.lines.get_nowait()
            except queue.Empty:
                break
            if "status" in line:
                self.status = line
            else:
                self.progress = line
        running = self.proc.poll() is None or self._reader.is_alive()
        if not running and self.status is None:
            self.poll_once_more()
        return running

    def poll_once_more(self):
        while not self.lines.empty():
            line = self.lines.get_nowait()
            if "status" in line:
                self.status = line
            else:
                self.progress = line

    def overall_fraction(self):
        """0..1 over both stages: simulating is most of the time (0-0.8), rendering the rest."""
        p = self.progress or {}
        f = float(p.get("fraction", 0.0))
        return 0.8 * f if p.get("stage") == "simulate" else 0.8 + 0.2 * f

    def status_text(self):
        p = self.progress
        if not p:
            return "jellysim: starting"
        eta = p.get("eta_seconds")
        left = f", {eta:.0f} s left" if isinstance(eta, (int, float)) else ""
        if p.get("stage") == "simulate":
            return f"jellysim: simulating {p.get('time', 0):.2f} / {p.get('duration', 0):.2f} s{left}"
        return f"jellysim: {p.get('stage')} {p.get('frames', '')}/{p.get('frames_total', '')}{left}"

    def cancel(self):
        """SIGINT: the CLI stops at its next step boundary and keeps what it wrote (status
        "interrupted")."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)

    def wait(self, timeout=None):
        self.proc.wait(timeout)
        self._reader.join(timeout)
        self.poll()
        return self.status
