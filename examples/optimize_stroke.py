"""Optimise the stroke for speed with jellysim.optimize (docs/control.md): the contraction
frequency and the pause after re-expansion (jellyfish.pause_fraction, the part of the cycle the bell
rests relaxed: Gemmell et al. 2013), on a coarse tank (96 x 192 cells) so that it takes a few
minutes on two cores.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/optimize_stroke.py --out out/optimize_stroke
"""
import argparse

import jellysim


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="out/optimize_stroke")
    parser.add_argument("--evaluations", type=int, default=20)
    parser.add_argument("--cells", type=int, nargs=2, default=[96, 192], help="fluid cells [nx ny]")
    args = parser.parse_args()
    plan = {
        "cycles": 3,
        "objective": "speed",
        "sense": "maximize",
        "algorithm": "bobyqa",
        "evaluations": args.evaluations,
        "seed": 1,
        "set": {"tank.cells": args.cells},
        "variables": {"jellyfish.frequency": [0.4, 1.4], "jellyfish.pause_fraction": [0.0, 0.5]},
    }
    summary = jellysim.optimize(plan, out=args.out, quiet=False)
    print(f"baseline speed {summary['baseline_objective'] * 100:.3f} cm/s, best {summary['best_objective'] * 100:.3f} cm/s "
          f"at {summary['best_variables']} after {summary['evaluations']} evaluations ({summary['wall_seconds']:.0f} s)")


if __name__ == "__main__":
    main()
