#!/usr/bin/env python3
"""How far the slice's tentacles lean in under the bell, per stroke (docs/jellyfish.md, "Tentacles
that trail").

Reads a run's slices.csv (`jellysim simulate` or `run` writes it) and prints, for each cycle's
contraction (phase 0 to `--contract-fraction`) and recovery (the rest), the mean and largest inward
lean of the tentacles and of the margin, and the smallest distance of a tentacle tip behind its root
along the swimming axis:

  * the axis is the frame's apex minus the aperture centre (the midpoint of the two margin tips);
  * a tentacle's lean is the angle of its root-to-tip direction from the trailing direction −axis,
    positive toward the axis (under the bell);
  * the margin's lean is that of the bell's last segment (next-to-last umbrella point to the tip).

    scripts/tentacle-lean.py out/run/slices.csv --frequency 0.7
"""
import argparse
import csv
import math
from collections import defaultdict


def read_frames(path):
    """{frame: (t, {part: {index: (x, y)}})} from slices.csv."""
    frames = defaultdict(lambda: [0.0, defaultdict(dict)])
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            frame = frames[int(float(row["frame"]))]
            frame[0] = float(row["t"])
            frame[1][row["part"]][int(float(row["index"]))] = (float(row["x"]), float(row["y"]))
    return frames


def lean(root, tip, axis, outward):
    """Angle (degrees) of root → tip from −axis, positive against `outward`; and the tip's distance
    behind the root along the axis (m)."""
    d = (tip[0] - root[0], tip[1] - root[1])
    behind = -(d[0] * axis[0] + d[1] * axis[1])
    across = d[0] * outward[0] + d[1] * outward[1]
    return math.degrees(math.atan2(-across, behind)), behind


def frame_leans(parts):
    """(tentacle lean, margin lean, tip behind root) of each side of one frame."""
    u = parts["umbrella"]
    n = len(u)
    apex, left, right = u[n // 2], u[0], u[n - 1]
    axis = (apex[0] - 0.5 * (left[0] + right[0]), apex[1] - 0.5 * (left[1] + right[1]))
    length = math.hypot(*axis)
    axis = (axis[0] / length, axis[1] / length)
    sides = []
    for name, tip_index, inner_index, outward in (("tentacle_0", 0, 1, (-axis[1], axis[0])),
                                                  ("tentacle_1", n - 1, n - 2, (axis[1], -axis[0]))):
        strand = parts[name]
        tentacle, behind = lean(strand[0], strand[max(strand)], axis, outward)
        margin, _ = lean(u[inner_index], u[tip_index], axis, outward)
        sides.append((tentacle, margin, behind))
    return sides


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("slices", help="slices.csv of a jellyfish run")
    parser.add_argument("--frequency", type=float, default=0.7, help="contraction frequency, Hz")
    parser.add_argument("--contract-fraction", type=float, default=0.3, help="part of the cycle spent contracting")
    args = parser.parse_args()
    strokes = defaultdict(list)
    for t, parts in read_frames(args.slices).values():
        phase = t * args.frequency
        cycle = int(phase)
        stroke = "contraction" if phase - cycle < args.contract_fraction else "recovery"
        strokes[(cycle + 1, stroke)].extend(frame_leans(parts))
    print("cycle,stroke,tentacle_lean_mean_deg,tentacle_lean_max_deg,margin_lean_mean_deg,margin_lean_max_deg,"
          "tip_behind_root_min_mm")
    for (cycle, stroke), sides in sorted(strokes.items()):
        tentacle = [s[0] for s in sides]
        margin = [s[1] for s in sides]
        print(f"{cycle},{stroke},{sum(tentacle) / len(tentacle):.1f},{max(tentacle):.1f},"
              f"{sum(margin) / len(margin):.1f},{max(margin):.1f},{1e3 * min(s[2] for s in sides):.2f}")


if __name__ == "__main__":
    main()
