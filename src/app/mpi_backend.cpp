// The MPI backend of `jellysim batch` (docs/batch.md) and of `jellysim optimize`'s Pareto sweep
// (docs/control.md): dynamic load balancing by a coordinator. Every rank reads and validates the
// plan; rank 0 checks the output directory (resume), then answers each worker's request with the
// next task index until none is left; a worker solves the task in-process (a batch run,
// experiments::Batch::run, or a Pareto sub-problem, experiments::ParetoSweep::solve: the same code
// as the threaded backends) and sends back its result as text; rank 0 writes the tables in task
// order. Only this file knows MPI.
#include "mpi_backend.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/experiments/batch.hpp"
#include "jellysim/experiments/optimize.hpp"
#include "jellysim/io/output.hpp"

#include <mpi.h>

#include <chrono>
#include <functional>
#include <cstdlib>
#include <iostream>
#include <optional>

namespace jellysim::app {
namespace {

using experiments::Batch;
using experiments::BatchRow;

enum Tag : int { kReady = 1, kWork = 2, kStop = 3, kRow = 4 };
constexpr int kExitBadInput = 2;

/// MPI_Init and, however this scope ends, MPI_Finalize.
struct MpiSession {
  MpiSession() { MPI_Init(nullptr, nullptr); }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
  }
  int size() const {
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
  }
};

/// A batch row as one message: flags, timing, rank, failure, then the cells, each ended by NUL
/// (no field holds one: --set values cannot).
std::string encode(const BatchRow& row) {
  std::string m;
  auto put = [&m](const std::string& field) {
    m += field;
    m.push_back('\0');
  };
  put(row.failed ? "1" : "0");
  put(row.interrupted ? "1" : "0");
  put(io::format_double(row.wall_seconds));
  put(std::to_string(row.rank));
  put(row.failure);
  for (const std::string& cell : row.cells) put(cell);
  return m;
}

BatchRow decode(const std::string& m) {
  std::vector<std::string> fields;
  for (std::size_t at = 0; at < m.size();) {
    const std::size_t end = m.find('\0', at);
    fields.push_back(m.substr(at, end - at));
    at = end + 1;
  }
  if (fields.size() < 5) throw RunError("batch: a worker's message is cut short");
  BatchRow row;
  row.failed = fields[0] == "1";
  row.interrupted = fields[1] == "1";
  row.wall_seconds = std::strtod(fields[2].c_str(), nullptr);
  row.rank = std::stoi(fields[3]);
  row.failure = fields[4];
  row.cells.assign(fields.begin() + 5, fields.end());
  return row;
}

/// True on every rank when `failed` is true on any.
bool any_rank(bool failed) {
  int mine = failed ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any != 0;
}

/// True on every rank when any rank's plan was bad; the error is printed once, by rank 0 when it
/// has one, else by each failing rank.
bool input_error_on_any_rank(const std::string& error, int rank) {
  int rank0_failed = rank == 0 && !error.empty() ? 1 : 0;
  MPI_Bcast(&rank0_failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!any_rank(!error.empty())) return false;
  if (!error.empty() && (rank == 0 || !rank0_failed)) std::cerr << "jellysim: error: " << error << "\n";
  return true;
}

std::string receive(MPI_Status& status) {
  MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
  int length = 0;
  MPI_Get_count(&status, MPI_CHAR, &length);
  std::string message(static_cast<std::size_t>(length), '\0');
  MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return message;
}

/// A task's result as sent: its index, NUL, then the payload.
using Accept = std::function<void(std::size_t, const std::string&)>;
using Solve = std::function<std::string(std::size_t)>;

/// Rank 0: hands out the tasks one at a time to whichever worker asks; `accept` hears each result.
void coordinate(const std::vector<std::size_t>& todo, int ranks, const Accept& accept) {
  std::size_t next = 0;
  for (int working = ranks - 1; working > 0;) {
    MPI_Status status;
    const std::string message = receive(status);
    if (status.MPI_TAG == kRow) {
      const std::size_t cut = message.find('\0');
      if (cut == std::string::npos) throw RunError("a worker's message is cut short");
      accept(std::stoul(message.substr(0, cut)), message.substr(cut + 1));
    }
    if (next < todo.size() && core::interrupt_signal() == 0) {
      const unsigned long long k = todo[next++];
      MPI_Send(&k, 1, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kWork, MPI_COMM_WORLD);
    } else {
      MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kStop, MPI_COMM_WORLD);
      --working;
    }
  }
}

/// The other ranks: ask for a task, solve it, send its result (which asks for the next), until
/// told to stop.
int work(const Solve& solve) {
  const SerialThreadsScope one_core;  // the ranks share the cores: a run's `threads = 0` is one
  MPI_Send(nullptr, 0, MPI_CHAR, 0, kReady, MPI_COMM_WORLD);
  for (;;) {
    unsigned long long k = 0;
    MPI_Status status;
    MPI_Recv(&k, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kStop) return 0;
    const std::string message = std::to_string(k) + '\0' + solve(static_cast<std::size_t>(k));
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kRow, MPI_COMM_WORLD);
  }
}

/// Rank 0 of a batch: the runs handed out, their rows in run order, batch.csv written.
int coordinate_batch(const Batch& batch, const std::vector<std::size_t>& todo, int ranks, bool quiet,
                     std::chrono::steady_clock::time_point start) {
  std::vector<BatchRow> rows = batch.starting_rows();
  coordinate(todo, ranks, [&](std::size_t k, const std::string& message) {
    BatchRow row = decode(message);
    experiments::report_batch_run(batch, k, row, quiet);
    rows.at(k) = std::move(row);
  });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return experiments::finish_batch(batch, rows, "MPI: " + std::to_string(ranks - 1) + " worker ranks", wall, quiet);
}

/// A worker of a batch: each run in-process, its row sent back.
int work_on_batch(const Batch& batch, int rank) {
  return work([&](std::size_t k) {
    BatchRow row = batch.run(k);
    row.rank = rank;
    return encode(row);
  });
}

/// Rank 0's check of the output directory, shared with every rank: the runs to do, or the error.
std::optional<std::vector<std::size_t>> prepare_on_rank0(Batch& batch, int rank, int& exit_code) {
  std::vector<std::size_t> todo;
  if (rank == 0) {
    try {
      todo = batch.prepare_directory();
    } catch (const InputError& e) {
      std::cerr << "jellysim: error: " << e.what() << "\n";
      exit_code = kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "jellysim: run failed: " << e.what() << "\n";
      exit_code = 1;
    }
  }
  if (any_rank(exit_code != 0)) return std::nullopt;
  return todo;
}

/// The plan of `optimize` under several ranks: only a Pareto sweep has independent work to share.
experiments::OptimizePlan read_plan_for_ranks(const std::filesystem::path& file) {
  experiments::OptimizePlan plan = experiments::read_optimize_plan(file);
  if (plan.objectives.size() != 2)
    throw InputError(file.string() + ": a single-objective search is one sequence of evaluations, each chosen from "
                     "the last: run it as one process. Under mpirun only a Pareto sweep (field 'objectives' = [a, b]) "
                     "spreads its sub-problems over the ranks");
  experiments::validate_plan_against_scene(plan);
  return plan;
}

/// Rank 0 of a Pareto sweep: the sub-problems handed out, their rows written as they come back.
int coordinate_sweep(experiments::ParetoSweep& sweep, int ranks, bool quiet, std::chrono::steady_clock::time_point start) {
  std::vector<std::size_t> todo(sweep.size());
  for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = k;
  coordinate(todo, ranks, [&](std::size_t k, const std::string& rows) {
    sweep.accept(k, rows);
    if (!quiet)
      std::cout << "sub-problem " << k << " (weight " << io::format_double(sweep.weight(k)) << "): "
                << sweep.evaluations(k) << " evaluations" << std::endl;
  });
  if (const int signal = core::interrupt_signal(); signal != 0) {
    std::cerr << "jellysim optimize: interrupted; evaluations.csv keeps the finished sub-problems (rerun to resume)\n";
    return 128 + signal;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sweep.finish("MPI: " + std::to_string(ranks - 1) + " worker ranks", wall);
  return 0;
}

}  // namespace

int run_optimize_mpi(const std::filesystem::path& plan_file, const std::filesystem::path& out, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  const MpiSession mpi;
  const int rank = mpi.rank(), ranks = mpi.size();
  std::optional<experiments::OptimizePlan> plan;
  std::string error;
  try {
    plan = ranks == 1 ? experiments::read_optimize_plan(plan_file) : read_plan_for_ranks(plan_file);
  } catch (const InputError& e) {
    error = e.what();
  }
  if (input_error_on_any_rank(error, rank)) return kExitBadInput;
  if (ranks == 1) {
    experiments::run_optimize(*plan, out, quiet);
    return 0;
  }
  // Every rank evaluates the baseline and reads the earlier evaluations.csv before rank 0 opens the
  // directory (and from then on rewrites that file).
  experiments::ParetoSweep sweep(*plan, out, true);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    try {
      sweep.open_output();
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  if (input_error_on_any_rank(error, rank)) return kExitBadInput;
  core::install_interrupt_handlers();
  try {
    return rank == 0 ? coordinate_sweep(sweep, ranks, quiet, start) : work([&](std::size_t k) { return sweep.solve(k); });
  } catch (const std::exception& e) {
    std::cerr << "jellysim optimize: rank " << rank << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
}

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

int run_batch_mpi(const std::filesystem::path& plan, const std::vector<std::string>& sets,
                  const std::filesystem::path& out, int threads, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  const MpiSession mpi;
  const int rank = mpi.rank(), ranks = mpi.size();
  if (ranks == 1) {
    Batch batch(experiments::read_batch_plan(plan), sets, out);
    return experiments::run_batch_threaded(batch, threads, quiet);
  }
  // Every rank validates the plan; the first rank with an error names it (rank 0 when it has one).
  std::optional<Batch> batch;
  std::string error;
  try {
    batch.emplace(experiments::read_batch_plan(plan), sets, out);
  } catch (const InputError& e) {
    error = e.what();
  }
  if (input_error_on_any_rank(error, rank)) return kExitBadInput;
  int exit_code = 0;
  const std::optional<std::vector<std::size_t>> todo = prepare_on_rank0(*batch, rank, exit_code);
  if (!todo) return exit_code;
  core::install_interrupt_handlers();
  try {
    return rank == 0 ? coordinate_batch(*batch, *todo, ranks, quiet, start) : work_on_batch(*batch, rank);
  } catch (const std::exception& e) {
    std::cerr << "jellysim batch: rank " << rank << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
}

}  // namespace jellysim::app
