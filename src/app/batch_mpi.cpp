// The MPI backend of `jellysim batch` (docs/batch.md): dynamic load balancing by a coordinator.
// Every rank reads and validates the plan; rank 0 checks the output directory (resume), then answers
// each worker's request with the next run index until none is left; a worker runs the run in-process
// (experiments::Batch::run, the same code as the threaded backend), writes its directory and sends
// back the row; rank 0 writes batch.csv in run order. Only this file knows MPI.
#include "batch_mpi.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/experiments/batch.hpp"
#include "jellysim/io/output.hpp"

#include <mpi.h>

#include <chrono>
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

/// A row as one message: index, flags, timing, rank, failure, then the cells, each ended by NUL
/// (no field holds one: --set values cannot).
std::string encode(std::size_t k, const BatchRow& row) {
  std::string m;
  auto put = [&m](const std::string& field) {
    m += field;
    m.push_back('\0');
  };
  put(std::to_string(k));
  put(row.failed ? "1" : "0");
  put(row.interrupted ? "1" : "0");
  put(io::format_double(row.wall_seconds));
  put(std::to_string(row.rank));
  put(row.failure);
  for (const std::string& cell : row.cells) put(cell);
  return m;
}

std::pair<std::size_t, BatchRow> decode(const std::string& m) {
  std::vector<std::string> fields;
  for (std::size_t at = 0; at < m.size();) {
    const std::size_t end = m.find('\0', at);
    fields.push_back(m.substr(at, end - at));
    at = end + 1;
  }
  if (fields.size() < 6) throw RunError("batch: a worker's message is cut short");
  BatchRow row;
  row.failed = fields[1] == "1";
  row.interrupted = fields[2] == "1";
  row.wall_seconds = std::strtod(fields[3].c_str(), nullptr);
  row.rank = std::stoi(fields[4]);
  row.failure = fields[5];
  row.cells.assign(fields.begin() + 6, fields.end());
  return {std::stoul(fields[0]), std::move(row)};
}

/// True on every rank when `failed` is true on any.
bool any_rank(bool failed) {
  int mine = failed ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any != 0;
}

std::string receive(MPI_Status& status) {
  MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
  int length = 0;
  MPI_Get_count(&status, MPI_CHAR, &length);
  std::string message(static_cast<std::size_t>(length), '\0');
  MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return message;
}

/// Rank 0: hands out the runs one at a time to whichever worker asks, collects the rows.
int coordinate(const Batch& batch, const std::vector<std::size_t>& todo, int ranks, bool quiet,
               std::chrono::steady_clock::time_point start) {
  std::vector<BatchRow> rows = batch.starting_rows();
  std::size_t next = 0;
  for (int working = ranks - 1; working > 0;) {
    MPI_Status status;
    const std::string message = receive(status);
    if (status.MPI_TAG == kRow) {
      auto [k, row] = decode(message);
      experiments::report_batch_run(batch, k, row, quiet);
      rows.at(k) = std::move(row);
    }
    if (next < todo.size() && core::interrupt_signal() == 0) {
      const unsigned long long k = todo[next++];
      MPI_Send(&k, 1, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kWork, MPI_COMM_WORLD);
    } else {
      MPI_Send(nullptr, 0, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kStop, MPI_COMM_WORLD);
      --working;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return experiments::finish_batch(batch, rows, "MPI: " + std::to_string(ranks - 1) + " worker ranks", wall, quiet);
}

/// The other ranks: ask for a run, run it, send its row (which asks for the next), until told to stop.
int work(const Batch& batch, int rank) {
  const SerialThreadsScope one_core;  // the ranks share the cores: a run's `threads = 0` is one
  MPI_Send(nullptr, 0, MPI_CHAR, 0, kReady, MPI_COMM_WORLD);
  for (;;) {
    unsigned long long k = 0;
    MPI_Status status;
    MPI_Recv(&k, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kStop) return 0;
    BatchRow row = batch.run(static_cast<std::size_t>(k));
    row.rank = rank;
    const std::string message = encode(static_cast<std::size_t>(k), row);
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kRow, MPI_COMM_WORLD);
  }
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

}  // namespace

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
  int rank0_failed = rank == 0 && !error.empty() ? 1 : 0;
  MPI_Bcast(&rank0_failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (any_rank(!error.empty())) {
    if (!error.empty() && (rank == 0 || !rank0_failed)) std::cerr << "jellysim: error: " << error << "\n";
    return kExitBadInput;
  }
  int exit_code = 0;
  const std::optional<std::vector<std::size_t>> todo = prepare_on_rank0(*batch, rank, exit_code);
  if (!todo) return exit_code;
  core::install_interrupt_handlers();
  try {
    return rank == 0 ? coordinate(*batch, *todo, ranks, quiet, start) : work(*batch, rank);
  } catch (const std::exception& e) {
    std::cerr << "jellysim batch: rank " << rank << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }
}

}  // namespace jellysim::app
