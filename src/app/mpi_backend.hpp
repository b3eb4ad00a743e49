#pragma once
// The MPI backend of `jellysim batch` and of `jellysim optimize`'s Pareto sweep (built when CMake
// finds MPI: JELLYSIM_MPI). Rank 0 checks the output directory and hands out task indices (runs,
// sub-problems) one at a time; the other ranks solve them and send back their rows; rank 0 writes
// the tables in task order, the same bytes as the threaded backend.
#include <filesystem>
#include <string>
#include <vector>

namespace jellysim::app {

/// True when an MPI launcher (mpirun, mpiexec, srun) started this process: only then is MPI
/// initialised, so the same binary runs alone without touching MPI.
bool launched_by_mpi();

/// Runs the batch over the ranks of MPI_COMM_WORLD (one rank: the threaded backend with `threads`).
/// Returns this rank's exit status (rank 0's is the batch's: 0, 2 for bad input, 128 + signal).
int run_batch_mpi(const std::filesystem::path& plan, const std::vector<std::string>& sets,
                  const std::filesystem::path& out, int threads, bool quiet);

/// Runs a two-objective optimize plan's sub-problems over the ranks of MPI_COMM_WORLD (one rank:
/// run_optimize). A single-objective plan under several ranks is refused (exit 2). Returns this
/// rank's exit status (rank 0's is the command's: 0, 2 for bad input, 128 + signal).
int run_optimize_mpi(const std::filesystem::path& plan, const std::filesystem::path& out, bool quiet);

}  // namespace jellysim::app
