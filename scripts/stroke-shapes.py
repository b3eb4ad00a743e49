#!/usr/bin/env python3
"""The bell's shape over one contraction cycle for several strokes, side by side (docs/control.md).

Reads each run's slices.csv (`jellysim simulate` writes it: the umbrella's points per frame) and
draws the umbrella at `--phases` evenly spaced phases of cycle `--cycle` (counted from 1), each
outline moved so that its apex sits at the origin, coloured by phase.

    scripts/stroke-shapes.py --out docs/images/stroke_shapes.png \
        "built-in, 0.7 Hz:out/base:0.7" "optimised, 0.4 Hz:out/opt:0.4"
"""
import argparse
import csv
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def umbrella_frames(path):
    """{frame time (s): [(x, y), ...]} of the umbrella's points, in point order."""
    frames = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["part"] == "umbrella":
                frames[float(row["t"])].append((float(row["x"]), float(row["y"])))
    return frames


def nearest_frame(frames, t):
    return min(frames, key=lambda s: abs(s - t))


def draw_stroke(ax, label, frames, frequency_hz, cycle, phases):
    cmap = plt.get_cmap("viridis")
    for k in range(phases):
        t = nearest_frame(frames, (cycle - 1 + k / phases) / frequency_hz)
        points = frames[t]
        apex = max(points, key=lambda p: p[1])
        xs = [100 * (x - apex[0]) for x, _ in points]
        ys = [100 * (y - apex[1]) for _, y in points]
        ax.plot(xs, ys, color=cmap(k / phases), lw=1.5, label=f"{k}/{phases} cycle")
    ax.set_title(label)
    ax.set_aspect("equal")
    ax.set_xlabel("x from the apex (cm)")
    ax.grid(True, alpha=0.3)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("strokes", nargs="+", help="LABEL:RUN_DIR:FREQUENCY_HZ")
    parser.add_argument("--cycle", type=int, default=2, help="which cycle (from 1; the first starts from rest)")
    parser.add_argument("--phases", type=int, default=8)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    fig, axes = plt.subplots(1, len(args.strokes), figsize=(4.2 * len(args.strokes), 4.2), sharey=True)
    axes = axes if len(args.strokes) > 1 else [axes]
    for ax, spec in zip(axes, args.strokes):
        label, run, frequency = spec.rsplit(":", 2)
        draw_stroke(ax, label, umbrella_frames(f"{run}/slices.csv"), float(frequency), args.cycle, args.phases)
    axes[0].set_ylabel("y from the apex (cm)")
    axes[-1].legend(fontsize=7, loc="lower right")
    fig.suptitle(f"The umbrella over cycle {args.cycle}, every 1/{args.phases} of a cycle")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
