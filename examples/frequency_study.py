#!/usr/bin/env python3
"""A small frequency sweep through the jellysim Python module (docs/python.md): the built-in
jellyfish on a coarse tank at a few contraction frequencies, the distance each swims per cycle (the
mean over the cycles after the first, which starts from rest), printed as a
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


def distance_per_cycle(frequency_hz, cycles):
    """Mean distance (m) the bell centroid travels along its axis per cycle, over the cycles after the
    first (the first starts from rest), at this frequency: the figure `jellysim simulate` reports."""
    scene = jellysim.load_scene(overrides={**COARSE, "jellyfish.frequency": frequency_hz})
    sim = jellysim.Simulation(scene)
    period = 1.0 / frequency_hz
    sim.advance(period)
    after_first = sim.metrics()["position"][-1]
    sim.advance((cycles - 1) * period)
    return (sim.metrics()["position"][-1] - after_first) / (cycles - 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frequencies", type=float, nargs="+", default=[0.5, 0.7, 0.9], help="Hz")
    parser.add_argument("--cycles", type=int, default=3, help="contraction cycles per run (at least 2)")
    parser.add_argument("--out", default="frequency_study.png", help="the plot (PNG)")
    args = parser.parse_args()
    if args.cycles < 2:
        parser.error("--cycles must be at least 2 (the first cycle starts from rest and is left out)")

    distances = [distance_per_cycle(f, args.cycles) for f in args.frequencies]
    print(f"{'frequency (Hz)':>15} {'distance per cycle (cm)':>24} {'mean speed (cm/s)':>18}")
    for f, d in zip(args.frequencies, distances):
        print(f"{f:15.3f} {100 * d:24.3f} {100 * d * f:18.3f}")

    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(args.frequencies, [100 * d for d in distances], "o-")
    ax.set_xlabel("contraction frequency (Hz)")
    ax.set_ylabel("distance per cycle after the first (cm)")
    ax.set_title("jellysim: distance against frequency")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"plot: {args.out}")


if __name__ == "__main__":
    main()
