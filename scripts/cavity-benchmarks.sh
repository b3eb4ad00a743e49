#!/usr/bin/env bash
# Driven-cavity benchmark against Ghia, Ghia & Shin (1982) (issue 20; docs/fluids.md): every
# combination of solver/scheme, Reynolds number and grid, each run to steady state with
# `jellysim experiment driven-cavity`, gathered into OUT/benchmarks.csv.
#   scripts/cavity-benchmarks.sh OUT [JOBS]
# Environment (space-separated lists): METHODS ("solver:scheme" pairs), RES, GRIDS, MAX_TIME (s);
# a run whose summary.json exists is not repeated.
# Needs a built build/release/jellysim (scripts/jellysim.sh build), or JELLYSIM=path.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: scripts/cavity-benchmarks.sh OUT [JOBS]}
jobs=${2:-1}
methods=${METHODS:-"eulerian:koren semi-lagrangian:maccormack eulerian:donor-cell semi-lagrangian:linear"}
res=${RES:-"100 400 1000 3200"}
grids=${GRIDS:-"128 256"}
max_time=${MAX_TIME:-200}
bin=${JELLYSIM:-build/release/jellysim}
[ -x "$bin" ] || { echo "no $bin: run scripts/jellysim.sh build first" >&2; exit 2; }
mkdir -p "$out"

run_one() {  # solver:scheme re grid
  local solver=${1%%:*} scheme=${1##*:} re=$2 grid=$3
  local key=convection
  [ "$solver" = semi-lagrangian ] && key=advection
  local dir="$out/$solver-$scheme-re$re-$grid"
  [ -f "$dir/summary.json" ] && return 0  # resumable: finished runs are kept
  "$bin" experiment driven-cavity --solver "$solver" --re "$re" --grid "$grid" --out "$dir" --quiet \
    --set "cavity.$key=$scheme" --set cavity.max_time="$max_time" --set figure_8_7.enabled=false \
    --set output.frame_interval=0 --set output.tracers_per_side=0
}
export -f run_one
export out bin max_time
for m in $methods; do for r in $res; do for g in $grids; do echo "$m $r $g"; done; done; done |
  xargs -P "$jobs" -L 1 bash -c 'run_one "$0" "$1" "$2"'

# One row per run from its summary.json (one "key": value per line).
figure() { sed -n "s/^  \"$2\": \(.*\),\{0,1\}$/\1/p" "$1" | head -n 1 | tr -d ','; }
columns="steady simulated_seconds steps wall_seconds final_change_rate ghia_max_abs_u_error ghia_max_abs_v_error vortex_centre_x vortex_centre_y psi_min ghia_vortex_centre_x ghia_vortex_centre_y ghia_psi_min"
{
  printf 'solver,scheme,re,grid'
  for c in $columns; do printf ',%s' "$c"; done
  printf '\n'
  for m in $methods; do for r in $res; do for g in $grids; do
    s="$out/${m%%:*}-${m##*:}-re$r-$g/summary.json"
    printf '%s,%s,%s,%s' "${m%%:*}" "${m##*:}" "$r" "$g"
    for c in $columns; do printf ',%s' "$(figure "$s" "$c")"; done
    printf '\n'
  done; done; done
} >"$out/benchmarks.csv"
echo "wrote $out/benchmarks.csv"
