// `jellysim batch`: the runs of a plan resolved and validated up front, each run done in-process
// like `jellysim simulate` into DIR/runs/NNNN/, finished runs found again on resume, and the
// combined tables (batch.csv, batch_timings.csv) written in run order (docs/batch.md).
#include "jellysim/experiments/batch.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/scene/resolve.hpp"

#include <atomic>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>

namespace jellysim::experiments {
namespace fs = std::filesystem;

namespace {

/// The figures of a run's summary.json that batch.csv holds, in this order (never a wall-clock one).
const std::vector<std::string> kFigures = {
    "distance_travelled", "distance_in_bell_heights", "lateral_drift", "mean_speed", "cycles",
    "volume_frequency", "min_volume_ratio", "min_aperture_ratio", "daniel_distance", "simulated_seconds",
    "steps", "smallest_step", "largest_step", "frames"};
/// The batch's own files in DIR (beside runs/).
const std::set<std::string> kBatchFiles = {"batch.csv", "batch_timings.csv", "summary.json", "manifest.txt"};

const Experiment& simulate_experiment() { return find_experiment("jellyfish"); }

std::string json_cell(const nlohmann::ordered_json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return v.dump();
  if (v.is_number()) return io::format_double(v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return "";
}

/// An override's cell: a string without its quotes, anything else as written in TOML.
std::string value_cell(const std::optional<std::string>& literal) {
  if (!literal) return "";
  if (literal->size() >= 2 && literal->front() == '"') return config::Config::parse("v = " + *literal, "plan").string("v");
  return *literal;
}

std::string describe_run(const BatchPlan& plan, std::size_t k) {
  std::string text;
  const std::vector<std::optional<std::string>> cells = plan.run(k);
  for (std::size_t i = 0; i < plan.keys.size(); ++i)
    if (cells[i]) text += (text.empty() ? "" : ", ") + plan.keys[i] + "=" + *cells[i];
  return "run " + std::to_string(k) + (text.empty() ? "" : " (" + text + ")");
}

/// The built-in jellyfish scene, the plan's scene file, its duration, [set] and the command line's
/// --set (scene::resolve_config; the plan's duration is its first override, so a --set overrides it).
config::Config base_config(const BatchPlan& plan, const std::vector<std::string>& sets) {
  scene::ConfigSources sources{{}, plan.scene.string(), "jellyfish", true};
  if (!plan.scene.empty()) sources.scene_file = config::Config::load(plan.scene);
  if (plan.duration) sources.sets.push_back("duration=" + io::format_double(*plan.duration));
  sources.sets.insert(sources.sets.end(), plan.shared.begin(), plan.shared.end());
  sources.sets.insert(sources.sets.end(), sets.begin(), sets.end());
  return scene::resolve_config(scene::builtin_jellyfish_scene(), sources, "the jellyfish scene");
}

/// A run's own small files (summary.json, manifest.txt): at most this many bytes.
constexpr std::uintmax_t kMaxRunFileBytes = 16u << 20;

/// A file a run wrote, as it is: only a regular file, never through a link (none when it is not one).
std::optional<std::string> read_run_file(const fs::path& path) {
  try {
    return io::read_regular_file(path, kMaxRunFileBytes, false);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

std::optional<nlohmann::ordered_json> read_json(const fs::path& path) {
  const std::optional<std::string> text = read_run_file(path);
  if (!text) return std::nullopt;
  try {
    return nlohmann::ordered_json::parse(*text);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

/// summary[key] when it is a string, else "" (an edited summary may hold anything).
std::string string_field(const nlohmann::ordered_json& summary, const char* key) {
  const auto it = summary.find(key);
  return it != summary.end() && it->is_string() ? it->get<std::string>() : std::string();
}

/// The first kFigures that only a scene with a jellyfish has (swim_figures: jellyfish_count > 0).
constexpr std::size_t kJellyfishFigures = 9;

/// Every figure batch.csv takes that the run has is there, a number (null: a value that was not
/// finite); a run without a jellyfish has no jellyfish figures.
bool figures_complete(const nlohmann::ordered_json& summary) {
  const auto count = summary.find("jellyfish_count");
  if (count == summary.end() || !count->is_number_unsigned()) return false;
  const std::size_t first = count->get<std::size_t>() > 0 ? 0 : kJellyfishFigures;
  return std::all_of(kFigures.begin() + static_cast<std::ptrdiff_t>(first), kFigures.end(), [&](const std::string& figure) {
    const auto it = summary.find(figure);
    return it != summary.end() && (it->is_number() || it->is_null());
  });
}

/// Every file the run's manifest lists is there, a regular file (not a link).
bool manifest_files_present(const fs::path& dir) {
  const std::optional<std::string> manifest = read_run_file(dir / io::kManifestName);
  if (!manifest) return false;
  std::istringstream lines(*manifest);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line.front() == '#') continue;
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(dir / line, ec))) return false;
  }
  return true;
}

bool digits_only(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::vector<std::string> batch_csv_columns(const BatchPlan& plan) {
  std::vector<std::string> columns{"run"};
  columns.insert(columns.end(), plan.keys.begin(), plan.keys.end());
  columns.insert(columns.end(), kFigures.begin(), kFigures.end());
  columns.push_back("failed");
  return columns;
}

Batch::Batch(BatchPlan plan, const std::vector<std::string>& sets, fs::path out)
    : plan_(std::move(plan)), out_(std::move(out)) {
  try {
    base_ = base_config(plan_, sets);
  } catch (const InputError& e) {
    throw InputError(plan_.file.string() + ": " + e.what());
  }
  for (std::size_t k : runs_to_validate()) {
    try {
      simulate_experiment().prepare(Context{config(k), {}});  // validates as `simulate` would; runs nothing
    } catch (const InputError& e) {
      throw InputError(plan_.file.string() + ": " + describe_run(plan_, k) + ": " + e.what());
    }
  }
  resumed_.resize(size());
}

config::Config Batch::config(std::size_t k) const {
  config::Config c = base_;
  const std::vector<std::optional<std::string>> cells = plan_.run(k);
  for (std::size_t i = 0; i < plan_.keys.size(); ++i)
    if (cells[i]) c.set(plan_.keys[i] + "=" + *cells[i]);
  return c;
}

/// Every run of a plan of at most kValidateEveryRun runs; of a larger plan, runs that together
/// hold every value of every key, so that a value wrong whatever it is combined with is found
/// before anything runs (a combination wrong only together is found when its run starts: a failed
/// row). [product]: run t takes value t mod n of a key of n values, for t below the longest list's
/// length. [[runs]]: the first run that holds a value (or leaves every key to the scene).
std::vector<std::size_t> Batch::runs_to_validate() const {
  std::vector<std::size_t> runs;
  if (size() <= kValidateEveryRun) {
    for (std::size_t k = 0; k < size(); ++k) runs.push_back(k);
  } else if (!plan_.product.empty()) {
    std::size_t longest = 0;
    for (const auto& values : plan_.product) longest = std::max(longest, values.size());
    for (std::size_t t = 0; t < longest; ++t) {
      std::size_t k = 0;
      for (const auto& values : plan_.product) k = k * values.size() + t % values.size();
      runs.push_back(k);
    }
  } else {
    std::set<std::pair<std::size_t, std::optional<std::string>>> seen;
    for (std::size_t k = 0; k < size(); ++k) {
      bool adds = false;
      for (std::size_t i = 0; i < plan_.keys.size(); ++i) adds = seen.insert({i, plan_.listed[k][i]}).second || adds;
      if (adds) runs.push_back(k);
    }
  }
  return runs;
}

fs::path Batch::run_dir(std::size_t k) const {
  const std::size_t width = std::max<std::size_t>(4, std::to_string(size() > 0 ? size() - 1 : 0).size());
  std::string id = std::to_string(k);
  id.insert(0, width - std::min(width, id.size()), '0');
  return out_ / "runs" / id;
}

std::vector<std::string> Batch::row_cells(std::size_t k, const nlohmann::ordered_json& summary, bool failed) const {
  std::vector<std::string> cells{std::to_string(k)};
  for (const auto& value : plan_.run(k)) cells.push_back(value_cell(value));
  for (const std::string& figure : kFigures)
    cells.push_back(summary.contains(figure) ? json_cell(summary[figure]) : "");
  cells.push_back(failed ? "true" : "false");
  return cells;
}

/// A run is finished when its summary.json is complete (status ok or failed, not interrupted) and
/// records the configuration this plan gives the run.
std::optional<BatchRow> Batch::finished_row(std::size_t k) const {
  const std::optional<nlohmann::ordered_json> summary = read_json(run_dir(k) / "summary.json");
  if (!summary || !summary->is_object() || string_field(*summary, "command") != "simulate") return std::nullopt;
  const std::string status = string_field(*summary, "status");
  if (status != "ok" && status != "failed") return std::nullopt;
  if (!summary->contains("config") || (*summary)["config"] != config(k).to_json()) return std::nullopt;
  if (!figures_complete(*summary) || !manifest_files_present(run_dir(k))) return std::nullopt;
  BatchRow row;
  row.failed = status == "failed";
  row.cells = row_cells(k, *summary, row.failed);
  row.failure = string_field(*summary, "failure");
  const auto wall = summary->find("wall_seconds");
  row.wall_seconds = wall != summary->end() && wall->is_number() ? wall->get<double>() : 0.0;
  row.resumed = true;
  return row;
}

namespace {

/// DIR may hold the batch's own files, leftover temporaries and runs/NNNN of this plan; anything else
/// is refused before anything is touched.
void check_batch_directory(const Batch& batch) {
  const fs::path& dir = batch.out();
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) throw InputError("--out '" + dir.string() + "' is not a directory");
  const std::string width = batch.run_dir(0).filename().string();
  // Links are never followed: the batch writes only inside DIR.
  const auto refuse_link = [&](const fs::directory_entry& entry, const std::string& name) {
    if (entry.is_symlink())
      throw InputError("--out '" + dir.string() + "': '" + name + "' is a symbolic link; a batch writes only inside " +
                       "its own directory: remove the link, or give a new directory");
  };
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name == io::kLockName) continue;  // the batch's lock (held)
    refuse_link(entry, name);
    if ((kBatchFiles.contains(name) || name.find(".tmp-") != std::string::npos) && entry.is_regular_file()) continue;
    if (name == "runs" && entry.is_directory()) continue;
    throw InputError("--out '" + dir.string() + "' holds '" + name + "', which is not a batch's: give a new directory");
  }
  if (!fs::is_directory(dir / "runs", ec)) return;
  for (const auto& entry : fs::directory_iterator(dir / "runs")) {
    const std::string name = entry.path().filename().string();
    refuse_link(entry, "runs/" + name);
    if (entry.is_directory() && digits_only(name) && name.size() == width.size() && std::stoul(name) < batch.size())
      continue;
    throw InputError("--out '" + dir.string() + "' holds runs/" + name + ", which this plan (" +
                     std::to_string(batch.size()) + " runs) does not have: give a new directory");
  }
}

}  // namespace

std::vector<std::size_t> Batch::prepare_directory() {
  lock_ = io::lock_directory(out_, "--out");  // held for the batch's life: one batch (or run) in DIR at a time
  check_batch_directory(*this);
  std::vector<std::size_t> todo;
  for (std::size_t k = 0; k < size(); ++k) {
    resumed_[k] = finished_row(k);
    if (resumed_[k]) continue;
    std::error_code ec;
    // An unfinished run's files go (a directory holding anything else is refused: InputError).
    if (fs::exists(run_dir(k), ec)) io::OutputDir::for_run(run_dir(k), simulate_experiment().name);
    todo.push_back(k);
  }
  // batch.csv exists only for a complete batch: an earlier one goes while runs are missing.
  if (!todo.empty())
    for (const std::string name : {"batch.csv", "batch_timings.csv", "summary.json"}) fs::remove(out_ / name);
  return todo;
}

std::vector<BatchRow> Batch::starting_rows() const {
  std::vector<BatchRow> rows(size());
  for (std::size_t k = 0; k < size(); ++k) {
    if (resumed_[k]) rows[k] = *resumed_[k];
    else rows[k].interrupted = true;  // until it has run
  }
  return rows;
}

BatchRow Batch::run(std::size_t k) const {
  const auto start = std::chrono::steady_clock::now();
  BatchRow row;
  try {
    const auto go = simulate_experiment().prepare(Context{config(k), {}});
    const io::OutputDir out = io::OutputDir::for_run(run_dir(k), simulate_experiment().name);
    const Outcome outcome = go(out);
    out.finish_manifest();
    const nlohmann::ordered_json summary = read_json(run_dir(k) / "summary.json").value_or(nlohmann::ordered_json::object());
    row.interrupted = string_field(summary, "status") == "interrupted";
    row.failed = !outcome.failure.empty();
    row.failure = outcome.failure;
    row.cells = row_cells(k, summary, row.failed);
  } catch (const std::exception& e) {
    row.failed = true;
    row.failure = e.what();
    row.cells = row_cells(k, nlohmann::ordered_json::object(), true);
  }
  row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

void Batch::write_tables(const std::vector<BatchRow>& rows, const std::string& backend, double wall_seconds) const {
  const io::OutputDir out(out_);
  io::CsvWriter csv(batch_csv_columns(plan_)), timings({"run", "rank", "wall_seconds", "resumed"});
  std::size_t failed = 0, resumed = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    csv.text_row(rows[k].cells);
    timings.text_row({std::to_string(k), rows[k].resumed ? "" : std::to_string(rows[k].rank),
                      io::format_double(rows[k].wall_seconds), rows[k].resumed ? "true" : "false"});
    failed += rows[k].failed ? 1 : 0;
    resumed += rows[k].resumed ? 1 : 0;
  }
  out.write_text("batch.csv", csv.text());
  out.write_text("batch_timings.csv", timings.text());
  nlohmann::ordered_json summary;
  summary["jellysim_version"] = JELLYSIM_VERSION;
  summary["command"] = "batch";
  summary["status"] = "ok";
  summary["plan"] = plan_.file.string();
  summary["runs"] = rows.size();
  summary["failed"] = failed;
  summary["resumed"] = resumed;
  summary["backend"] = backend;
  summary["wall_seconds"] = wall_seconds;
  out.write_json("summary.json", summary);
  out.write_text(io::kManifestName, "# jellysim batch: the batch's own files; each run's are listed in runs/NNNN/manifest.txt\n"
                                    "batch.csv\nbatch_timings.csv\nsummary.json\n");
}

int finish_batch(const Batch& batch, const std::vector<BatchRow>& rows, const std::string& backend,
                 double wall_seconds, bool quiet) {
  std::size_t unfinished = 0, failed = 0, resumed = 0;
  for (const BatchRow& r : rows) {
    unfinished += r.interrupted ? 1 : 0;
    failed += r.failed && !r.interrupted ? 1 : 0;
    resumed += r.resumed ? 1 : 0;
  }
  if (unfinished > 0) {
    const int signal = core::interrupt_signal() != 0 ? core::interrupt_signal() : SIGTERM;
    std::cerr << "jellysim batch: interrupted with " << unfinished << " of " << rows.size()
              << " runs unfinished; run the same command again to complete them\n";
    return 128 + signal;
  }
  batch.write_tables(rows, backend, wall_seconds);
  if (failed > 0) std::cerr << "jellysim batch: " << failed << " of " << rows.size() << " runs failed (failed = true in batch.csv)\n";
  if (!quiet)
    std::cout << "batch: " << rows.size() << " runs (" << rows.size() - resumed << " run now, " << resumed
              << " resumed, " << failed << " failed; " << backend << "): " << (batch.out() / "batch.csv").string() << "\n";
  return 0;
}

void report_batch_run(const Batch& batch, std::size_t k, const BatchRow& row, bool quiet) {
  static std::mutex lock;
  const std::lock_guard<std::mutex> guard(lock);
  const std::string name = batch.run_dir(k).lexically_relative(batch.out()).string();
  if (row.failed && !row.interrupted)
    std::cerr << "jellysim batch: " << name << " failed: " << row.failure << "\n";
  else if (!quiet)
    std::cout << name << (row.interrupted ? " interrupted" : " done") << " (" << io::format_double(row.wall_seconds)
              << " s)" << std::endl;
}

int run_batch_threaded(Batch& batch, int threads, bool quiet,
                       const std::function<void(std::size_t done, std::size_t total)>& on_run) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::size_t> todo = batch.prepare_directory();
  std::vector<BatchRow> rows = batch.starting_rows();
  const int workers = std::max(1, std::min(resolve_threads(threads), static_cast<int>(todo.size())));
  core::install_interrupt_handlers();
  WorkerPool pool(workers);
  std::atomic<std::size_t> done{0};
  if (on_run) on_run(0, todo.size());
  pool.run_tasks(todo.size(), [&](std::size_t i) {
    if (core::interrupt_signal() != 0) return;  // stopping: the runs not started stay unfinished
    rows[todo[i]] = batch.run(todo[i]);
    report_batch_run(batch, todo[i], rows[todo[i]], quiet);
    if (on_run) on_run(++done, todo.size());
  });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return finish_batch(batch, rows, "threads: " + std::to_string(workers), wall, quiet);
}

}  // namespace jellysim::experiments
