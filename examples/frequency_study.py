#!/usr/bin/env python3
"""A small frequency sweep through the jellysim Python module (docs/python.md): the built-in
jellyfish on a coarse tank at a few contraction frequencies, the distance each swims, printed as a
table and plotted against frequency with matplotlib (a PNG, no display needed).

    PYTHONPATH=build/release/python python3 examples/frequency_study.py --out frequency_study.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files only: no display
import matplotlib.pyplot as plt  # noqa: E402

import jellysim  # noqa: E402

# A coarse tank and no per-frame files: a few seconds per simulated second.
COARSE = {"tank.cells": [48, 96], "output.pictures": False, "output.vtk": False}


def distance_swum(frequency_hz, duration_s):
    """Distance (m) the bell centroid travels along its axis in duration_s at this frequency."""
    scene = jellysim.load_scene(overrides={**COARSE, "jellyfish.frequency": frequency_hz})
    sim = jellysim.Simulation(scene)
    sim.advance(duration_s)
    return sim.metrics()["position"][-1]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frequencies", type=float, nargs="+", default=[0.5, 0.7, 0.9], help="Hz")
    parser.add_argument("--duration", type=float, default=3.0, help="simulated seconds per run")
    parser.add_argument("--out", default="frequency_study.png", help="the plot (PNG)")
    args = parser.parse_args()

    distances = [distance_swum(f, args.duration) for f in args.frequencies]
    print(f"{'frequency (Hz)':>15} {'distance (cm)':>14} {'mean speed (cm/s)':>18}")
    for f, d in zip(args.frequencies, distances):
        print(f"{f:15.3f} {100 * d:14.3f} {100 * d / args.duration:18.3f}")

    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(args.frequencies, [100 * d for d in distances], "o-")
    ax.set_xlabel("contraction frequency (Hz)")
    ax.set_ylabel(f"distance in {args.duration:g} s (cm)")
    ax.set_title("jellysim: distance against frequency")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"plot: {args.out}")


if __name__ == "__main__":
    main()
