#!/usr/bin/env bash
# The built-in jellyfish with every convection/advection scheme at the built-in resolution and at
# twice it (issue 20, docs/jellyfish.md): distance per contraction cycle, from `jellysim simulate`.
#   scripts/jellyfish-schemes.sh OUT [JOBS]
# Environment: CYCLES (default 5; cycle 1 is the start from rest and is left out of the mean),
# METHODS ("solver:scheme" pairs), GRIDS ("NXxNY" sizes), JELLYSIM (default build/release/jellysim).
# A run whose summary.json exists is not repeated. Writes OUT/schemes.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: scripts/jellyfish-schemes.sh OUT [JOBS]}
jobs=${2:-1}
cycles=${CYCLES:-5}
methods=${METHODS:-"eulerian:donor-cell eulerian:van-leer eulerian:koren semi-lagrangian:linear semi-lagrangian:maccormack semi-lagrangian:bfecc"}
grids=${GRIDS:-"96x128 192x256"}
bin=${JELLYSIM:-build/release/jellysim}
[ -x "$bin" ] || { echo "no $bin: run scripts/jellysim.sh build first" >&2; exit 2; }
frequency=$(sed -n 's/^frequency = \([0-9.e-]*\).*/\1/p' scenes/jellyfish.toml | head -n 1)
duration=$(awk -v c="$cycles" -v f="$frequency" 'BEGIN { printf "%.17g", c / f }')
mkdir -p "$out"

run_one() {  # solver:scheme NXxNY
  local solver=${1%%:*} scheme=${1##*:} nx=${2%x*} ny=${2#*x}
  local key=convection
  [ "$solver" = semi-lagrangian ] && key=advection
  local dir="$out/$solver-$scheme-$2"
  [ -f "$dir/summary.json" ] && return 0
  "$bin" simulate --quiet --duration "$duration" --out "$dir" --set tank.solver="$solver" \
    --set "tank.$key=$scheme" --set "tank.cells=[$nx, $ny]"
}
export -f run_one
export out bin duration
for m in $methods; do for g in $grids; do echo "$m $g"; done; done | xargs -P "$jobs" -L 1 bash -c 'run_one "$0" "$1"'

figure() { sed -n "s/^  \"$2\": \(.*\),\{0,1\}$/\1/p" "$1" | head -n 1 | tr -d ','; }
{
  echo "solver,scheme,cells_x,cells_y,cycles,first_cycle_m,distance_per_cycle_m,steps,wall_seconds"
  for m in $methods; do for g in $grids; do
    dir="$out/${m%%:*}-${m##*:}-$g"
    # Bell position (metrics.csv column 2) at the sample nearest to the end of each cycle.
    per_cycle=$(awk -F, -v f="$frequency" -v n="$cycles" 'NR > 1 {
        k = int($1 * f + 0.5); d = $1 * f - k; if (d < 0) d = -d
        if (k <= n && (!(k in best) || d < best[k])) { best[k] = d; pos[k] = $2 } }
      END { printf "%.6g,%.6g", pos[1] - pos[0], (pos[n] - pos[1]) / (n - 1) }' "$dir/metrics.csv")
    printf '%s,%s,%s,%s,%s,%s,%s,%s\n' "${m%%:*}" "${m##*:}" "${g%x*}" "${g#*x}" "$cycles" "$per_cycle" \
      "$(figure "$dir/summary.json" steps)" "$(figure "$dir/summary.json" wall_seconds)"
  done; done
} >"$out/schemes.csv"
echo "wrote $out/schemes.csv"
