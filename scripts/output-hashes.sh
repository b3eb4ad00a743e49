#!/usr/bin/env bash
# Fingerprints of what the commands write, for refactors that must not change behaviour (issue 18):
# runs the main job (`jellysim run`, 3D outputs off) and every experiment with its defaults, and prints
# one line per CSV file: "sha256  command/file". Columns that time the run (names with "wall",
# "cpu_seconds", "seconds_per_") are dropped before hashing; everything else must be byte-identical.
#   scripts/output-hashes.sh [JELLYSIM] > docs/output-hashes.txt        record (after a change meant to alter results)
#   diff <(scripts/output-hashes.sh) docs/output-hashes.txt              compare (docs/architecture.md)
# It takes about 7 minutes on two cores (2026-11-28); it is a command, not a test.
set -euo pipefail
cd "$(dirname "$0")/.."
jellysim=$(realpath "${1:-build/release/jellysim}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Hash a CSV without its timing columns.
hash_csv() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = ($i !~ /wall|cpu_seconds|seconds_per_/) }
           { line = ""; sep = ""; for (i = 1; i <= NF; ++i) if (keep[i]) { line = line sep $i; sep = "," } print line }' "$1" |
    sha256sum | cut -d' ' -f1
}

run() {  # run NAME ARGS...: one command into $work/NAME, then its CSVs' hashes
  local name=$1; shift
  "$jellysim" "$@" --quiet --out "$work/$name" >"$work/$name.log" 2>&1 || { cat "$work/$name.log" >&2; exit 1; }
  (cd "$work/$name" && find . -name '*.csv' | sort) | while read -r f; do
    echo "$(hash_csv "$work/$name/$f")  $name/${f#./}"
  done
}

# The main job on the preview grid (96 x 192 cells), as tests/app/test_determinism.cpp runs it.
run run run --set render.png_frames=false --set render.video=false --set render.glb=false --set render.viewer=false \
  --set 'tank.cells=[96,192]'
for e in $("$jellysim" scenes | cut -f1); do
  case "$e" in
    jellyfish|animation) continue ;;  # `simulate` and `run` (above) run these
    3d-vs-axisymmetric) run "$e" experiment "$e" --set 'tank.cells=[32,48,32]' ;;  # 8 cells across the bell: 30 s, not 5 min
    *) run "$e" experiment "$e" ;;
  esac
done
run simulate simulate --duration 4.2857142857 --set output.pictures=false --set output.vtk=false
# The 3D scene (issue 40) on 8 cells across the bell, one cycle.
run simulate-3d simulate scenes/jellyfish-3d.toml --set 'tank.cells=[32,48,32]' --duration 1.4285714286
