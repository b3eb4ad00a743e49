#!/usr/bin/env bash
# Wall seconds per simulated second and Krylov iterations per step, side by side for two binaries
# (docs/benchmarks.md, "Per step and per grid"): one contraction cycle of the built-in scene at 16,
# 32 and 64 cells across the bell (outputs off) and one stroke of IB2d's Hoover–Miller bell at
# N = 256 and 512, each with BEFORE, then AFTER with coupling.threads = 1 and 2, alternating.
#   scripts/bench-steps.sh BEFORE_JELLYSIM [AFTER_JELLYSIM] [ROUNDS]
# It takes about ten minutes on two cores; it is a command, not a test.
set -euo pipefail
before=$(realpath "$1")
after=$(realpath "${2:-build/release/jellysim}")
rounds=${3:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

report() {  # report SUMMARY LABEL
  /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
w = d.get("wall_seconds_per_simulated_second") or d["wall_seconds"] / d["simulated_seconds"]
print("%-40s wall_s_per_sim_s %7.3f  krylov_per_step %.3f  steps %d" % (sys.argv[2], w, d["krylov_iterations"] / d["steps"], d["steps"]))
' "$1" "$2"
}

one() {  # one LABEL BINARY VARIANT ARGS...
  local label=$1 binary=$2 variant=$3; shift 3
  local threads=()
  [ "$variant" != before ] && threads=(--set "coupling.threads=${variant#threads}")
  rm -rf "$work/run"
  "$binary" "$@" "${threads[@]}" --out "$work/run" --quiet
  report "$work/run/summary.json" "$label $variant"
}

for round in $(seq "$rounds"); do
  for cells in "[96,192]" "[192,384]" "[384,768]"; do
    for variant in before threads1 threads2; do
      binary=$after; [ $variant = before ] && binary=$before
      one "round $round built-in $cells" "$binary" $variant simulate --duration 1.4285714285714286 \
        --set output.pictures=false --set output.vtk=false --set "tank.cells=$cells"
    done
  done
  for grid in 256 512; do
    for variant in before threads1 threads2; do
      binary=$after; [ $variant = before ] && binary=$before
      one "round $round hoover-miller N=$grid" "$binary" $variant experiment hoover-miller --grid $grid --cycles 1
    done
  done
  echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
done
