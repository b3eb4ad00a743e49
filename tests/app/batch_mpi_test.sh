#!/usr/bin/env bash
# CTest Batch.MpiMatchesThreads (registered when the MPI backend is built, tests/CMakeLists.txt):
# `mpirun -n 3 --oversubscribe jellysim batch` on loopback writes the same batch.csv, byte for byte,
# as the threaded backend; the worker ranks ran the runs; a batch with a run missing resumes under
# MPI too. Usage: batch_mpi_test.sh JELLYSIM MPIRUN WORKDIR
set -euo pipefail
jellysim=$1
mpirun=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
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
