#!/usr/bin/env bash
# The MPI backend (src/app/mpi_backend.cpp) against the threaded one, on loopback, byte for byte
# (registered when the MPI backend is built, tests/CMakeLists.txt). Usage:
#   mpi_backend_test.sh batch|optimize JELLYSIM MPIRUN WORKDIR
# batch (CTest Batch.MpiMatchesThreads): `mpirun -n 3 --oversubscribe jellysim batch` writes the same
#   batch.csv as the threaded backend; the worker ranks ran the runs; a batch with a run missing
#   resumes under MPI too.
# optimize (CTest Optimize.ParetoOverMpiMatchesThreads): `mpirun -n 3 jellysim optimize` of a
#   two-objective plan hands the Pareto sweep's sub-problems to the worker ranks and writes the same
#   evaluations.csv and pareto.csv as the threaded sweep; a rerun under MPI replays every evaluation;
#   a single-objective plan under several ranks is refused (exit 2).
set -euo pipefail
what=$1
jellysim=$2
mpirun=$3
work=$4
rm -rf "$work"
mkdir -p "$work"

batch_over_mpi() {
# Runs of different lengths, and one that fails (its fluid may not move at all).
cat >"$work/plan.toml" <<'PLAN'
duration = 0.1
[set]
"tank.cells" = [48, 64]
"output.pictures" = false
"output.vtk" = false
[[runs]]
"jellyfish.frequency" = 0.5
[[runs]]
"jellyfish.frequency" = 0.9
duration = 0.3
[[runs]]
"stability.max_speed" = 1e-9
[[runs]]
"jellyfish.gamma" = 0.6
[[runs]]
"jellyfish.frequency" = 0.7
"jellyfish.gamma" = 0.5
PLAN

"$jellysim" batch "$work/plan.toml" --quiet --threads 2 --out "$work/threads"
"$mpirun" -n 3 --oversubscribe "$jellysim" batch "$work/plan.toml" --out "$work/mpi" | tee "$work/mpi.log"
cmp "$work/threads/batch.csv" "$work/mpi/batch.csv"
grep -q "MPI: 2 worker ranks" "$work/mpi.log"
# Every run was run by a worker rank (1 or 2); rank 0 only hands them out.
awk -F, 'NR > 1 && $2 != 1 && $2 != 2 { print "run " $1 " ran on rank " $2; bad = 1 } END { exit bad }' \
  "$work/mpi/batch_timings.csv"
grep -q ',true$' "$work/mpi/batch.csv"

# Resume under MPI: a run's summary.json gone (as if killed in that run), only that run is redone.
rm "$work/mpi/runs/0003/summary.json" "$work/mpi/batch.csv"
"$mpirun" -n 3 --oversubscribe "$jellysim" batch "$work/plan.toml" --out "$work/mpi" | tee "$work/resume.log"
grep -q "1 run now, 4 resumed" "$work/resume.log"
cmp "$work/threads/batch.csv" "$work/mpi/batch.csv"
rm -rf "$work"
echo "batch over MPI: batch.csv identical to the threaded one"
}

optimize_over_mpi() {
cat >"$work/pareto.toml" <<'PLAN'
cycles = 2
objectives = ["speed", "cost_of_transport"]
algorithm = "cobyla"
evaluations = 6
pareto_points = 2
[set]
"tank.cells" = [48, 64]
"output.pictures" = false
"output.vtk" = false
[variables]
"jellyfish.frequency" = [1.0, 2.0]
PLAN

"$jellysim" optimize "$work/pareto.toml" --quiet --out "$work/threads"
"$mpirun" -n 3 --oversubscribe "$jellysim" optimize "$work/pareto.toml" --out "$work/mpi" | tee "$work/mpi.log"
cmp "$work/threads/evaluations.csv" "$work/mpi/evaluations.csv"
cmp "$work/threads/pareto.csv" "$work/mpi/pareto.csv"
grep -q '"engine": "MPI: 2 worker ranks"' "$work/mpi/summary.json"
grep -q 'sub-problem 1 (weight 1): 3 evaluations' "$work/mpi.log"

# A rerun into the same directory replays every evaluation (none is run again): the same bytes.
cp "$work/mpi/evaluations.csv" "$work/first.csv"
"$mpirun" -n 3 --oversubscribe "$jellysim" optimize "$work/pareto.toml" --quiet --out "$work/mpi"
cmp "$work/first.csv" "$work/mpi/evaluations.csv"

# One objective: a sequence of evaluations, refused under several ranks.
sed -e 's/^objectives = .*/objective = "speed"/' -e '/^pareto_points/d' "$work/pareto.toml" >"$work/single.toml"
set +e
"$mpirun" -n 2 --oversubscribe "$jellysim" optimize "$work/single.toml" --out "$work/single" 2>"$work/single.log"
code=$?
set -e
cat "$work/single.log"
[ "$code" -eq 2 ]
grep -q "single-objective search is one sequence of evaluations" "$work/single.log"
[ ! -e "$work/single" ]
rm -rf "$work"
echo "optimize over MPI: evaluations.csv and pareto.csv identical to the threaded sweep"
}

case "$what" in
  batch) batch_over_mpi ;;
  optimize) optimize_over_mpi ;;
  *) echo "usage: mpi_backend_test.sh batch|optimize JELLYSIM MPIRUN WORKDIR" >&2; exit 2 ;;
esac
