#pragma once
// `jellysim batch PLAN.toml --out DIR`: many jellyfish runs, each a `jellysim simulate` of the
// plan's scene with its own --set overrides, written to DIR/runs/NNNN/, and one combined table
// DIR/batch.csv (docs/batch.md). This file holds the plan, the runs and the tables; the threaded
// backend is run_batch_threaded, the MPI backend lives in the app (src/app/mpi_backend.cpp) and uses
// the same pieces, so both write the same bytes.
#include "jellysim/config/config.hpp"
#include "jellysim/io/output.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace jellysim::experiments {

/// A plan file as read: the scene, the duration, the overrides every run shares and the runs.
struct BatchPlan {
  std::filesystem::path file;          ///< the plan file (named in error messages)
  std::filesystem::path scene;         ///< resolved against the plan's directory; empty: the built-in scene
  std::optional<double> duration;      ///< seconds, for every run
  std::vector<std::string> shared;     ///< [set]: key=value assignments for every run, plan order
  std::vector<std::string> keys;       ///< the overridden keys, plan order (batch.csv's columns)
  /// [product]: per key, its values as TOML text (e.g. 0.5, "fft", [24, 32]); the runs are not
  /// stored (a product of 100 000 runs is a few lists): run(k) makes run k's. Empty for [[runs]].
  std::vector<std::vector<std::string>> product;
  /// [[runs]]: per run, per key: the value as TOML text; none: the scene's value.
  std::vector<std::vector<std::optional<std::string>>> listed;

  std::size_t run_count() const;
  /// Run k's value per key (none: the scene's value); [product]: the last key varying fastest.
  std::vector<std::optional<std::string>> run(std::size_t k) const;
};

/// Parses a plan (`text` read from `file`): top-level `scene`, `duration`, `[set]`, and either
/// `[product]` (every combination, the last key varying fastest) or `[[runs]]` (one table per run).
/// Throws InputError naming the file and the field.
BatchPlan parse_batch_plan(std::string_view text, const std::filesystem::path& file);
BatchPlan read_batch_plan(const std::filesystem::path& file);

/// One run's outcome as a row of batch.csv, plus what goes to batch_timings.csv and the console.
struct BatchRow {
  std::vector<std::string> cells;  ///< batch.csv's cells, numbers as io::format_double writes them
  bool failed = false;      ///< the run failed (its row says failed = true)
  bool interrupted = false; ///< stopped by SIGINT/SIGTERM: not finished, the next run resumes it
  bool resumed = false;     ///< found finished in DIR, not run again
  double wall_seconds = 0.0;
  int rank = 0;             ///< which MPI rank ran it (0 for the threaded backend)
  std::string failure;      ///< the failure message, if any
};

/// A batch: every run's configuration resolved and validated before anything is written.
class Batch {
 public:
  /// Plans of up to this many runs have every run validated before anything runs.
  static constexpr std::size_t kValidateEveryRun = 1000;

  /// Resolves each run: the built-in jellyfish scene, the plan's scene file, duration, [set], the
  /// command line's `sets`, then the run's overrides; each is validated as `simulate` would (a
  /// plan of more than kValidateEveryRun runs: runs that together hold every value of every key,
  /// see runs_to_validate). Throws InputError naming the plan file, the run and the field.
  Batch(BatchPlan plan, const std::vector<std::string>& sets, std::filesystem::path out);

  std::size_t size() const { return plan_.run_count(); }
  /// Run k's resolved configuration (made when asked: a batch keeps only the plan).
  config::Config config(std::size_t k) const;
  const BatchPlan& plan() const { return plan_; }
  const std::filesystem::path& out() const { return out_; }
  /// DIR/runs/NNNN (four digits at least).
  std::filesystem::path run_dir(std::size_t k) const;

  /// Locks DIR for the batch's life (another batch or run there: InputError naming its pid), checks
  /// it (new, or holding only an earlier batch's files, no symbolic link: else InputError, nothing touched),
  /// clears the directories of unfinished runs and returns the runs still to do, in order. The
  /// rows of finished runs (summary.json a regular file, complete, every figure a number, the same
  /// configuration; every file of the run's manifest there) are kept for tables().
  std::vector<std::size_t> prepare_directory();
  /// One row per run before any runs: the rows of the runs prepare_directory() found finished,
  /// the others marked unfinished (interrupted) until a row for them comes in.
  std::vector<BatchRow> starting_rows() const;

  /// Runs run k in this process like `jellysim simulate` (single-threaded, no progress display)
  /// into run_dir(k); its row comes from the summary.json it wrote. Never throws for a run that
  /// fails: an exception becomes a failed row.
  BatchRow run(std::size_t k) const;

  /// Writes batch.csv (rows in run order), batch_timings.csv, summary.json and manifest.txt.
  /// `rows` has one entry per run. `backend` describes what ran it (e.g. "threads: 4").
  void write_tables(const std::vector<BatchRow>& rows, const std::string& backend, double wall_seconds) const;

 private:
  std::optional<BatchRow> finished_row(std::size_t k) const;
  std::vector<std::string> row_cells(std::size_t k, const nlohmann::ordered_json& summary, bool failed) const;

  std::vector<std::size_t> runs_to_validate() const;

  BatchPlan plan_;
  std::filesystem::path out_;
  config::Config base_;  ///< every run's configuration before its own overrides
  std::vector<std::optional<BatchRow>> resumed_;
  std::shared_ptr<io::DirectoryLock> lock_;  ///< DIR's, from prepare_directory() on
};

/// batch.csv's columns: run, the plan's keys, then the figures and `failed`.
std::vector<std::string> batch_csv_columns(const BatchPlan& plan);

/// Runs the batch on `threads` workers (0: one per core) in this process, each taking the next
/// unfinished run; writes the tables unless interrupted. Returns the exit status: 0 when every run
/// finished (failed runs included), 128 + signal when interrupted. `on_run` (optional) hears of each
/// run finished: how many of the runs to do are done (`--progress json`).
int run_batch_threaded(Batch& batch, int threads, bool quiet,
                       const std::function<void(std::size_t done, std::size_t total)>& on_run = {});

/// One line for a run just done: on stderr when it failed, else on stdout unless `quiet`.
void report_batch_run(const Batch& batch, std::size_t k, const BatchRow& row, bool quiet);

/// Prints the closing lines (how many ran, were resumed, failed) and returns the exit status for
/// the finished rows (0, or 128 + signal when a run was interrupted). Shared by both backends.
int finish_batch(const Batch& batch, const std::vector<BatchRow>& rows, const std::string& backend,
                 double wall_seconds, bool quiet);

}  // namespace jellysim::experiments
