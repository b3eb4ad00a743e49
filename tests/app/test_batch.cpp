// `jellysim batch` (docs/batch.md): the plan's reading and validation, the threaded backend's
// batch.csv, a failing run's row, and resuming a killed batch. The MPI backend's byte-for-byte
// comparison with the threaded one is tests/app/mpi_backend_test.sh (registered when MPI is built).
#include <gtest/gtest.h>

#include "../cli_runner.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/batch.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
namespace cli = jellysim::testing;
using jellysim::InputError;
using jellysim::experiments::parse_batch_plan;

namespace {

// A coarse tank and short runs: each takes well under a second.
constexpr const char* kQuick =
    "duration = 0.1\n"
    "[set]\n"
    "\"tank.cells\" = [48, 64]\n"
    "\"output.pictures\" = false\n"
    "\"output.vtk\" = false\n";

fs::path write_plan(const fs::path& dir, const std::string& text) {
  fs::create_directories(dir);
  std::ofstream(dir / "plan.toml") << text;
  return dir / "plan.toml";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string error_of(const std::string& text) {
  try {
    parse_batch_plan(text, "plan.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

// [product]: every combination in plan order, the last key varying fastest; values become --set text.
TEST(BatchPlan, ProductVariesTheLastKeyFastest) {
  const auto plan = parse_batch_plan(
      "scene = \"scenes/fine.toml\"\nduration = 2\n[product]\n\"jellyfish.frequency\" = [0.5, 0.7, 0.9]\n"
      "jellyfish.gamma = [0.5, 0.6]\n\"tank.solver\" = [\"fft\"]\n",
      "/plans/p.toml");
  EXPECT_EQ(plan.scene, fs::path("/plans/scenes/fine.toml"));
  ASSERT_TRUE(plan.duration);
  EXPECT_EQ(*plan.duration, 2.0);
  EXPECT_EQ(plan.keys, (std::vector<std::string>{"jellyfish.frequency", "jellyfish.gamma", "tank.solver"}));
  ASSERT_EQ(plan.run_count(), 6u);
  EXPECT_EQ(*plan.run(0)[0], "0.5");
  EXPECT_EQ(*plan.run(0)[1], "0.5");
  EXPECT_EQ(*plan.run(1)[1], "0.6");
  EXPECT_EQ(*plan.run(2)[0], "0.7");
  EXPECT_EQ(*plan.run(5)[0], "0.9");
  EXPECT_EQ(*plan.run(5)[2], "\"fft\"");
}

// [[runs]]: one run per table, the columns in order of first appearance, absent keys left to the scene.
TEST(BatchPlan, RunsListTakesEachTableAsARun) {
  const auto plan = parse_batch_plan(
      "[set]\n\"output.vtk\" = false\n[[runs]]\n\"tank.cells\" = [24, 32]\n[[runs]]\njellyfish.frequency = 0.9\n"
      "\"tank.cells\" = [48, 64]\n",
      "p.toml");
  EXPECT_EQ(plan.shared, std::vector<std::string>{"output.vtk=false"});
  EXPECT_EQ(plan.keys, (std::vector<std::string>{"tank.cells", "jellyfish.frequency"}));
  ASSERT_EQ(plan.run_count(), 2u);
  EXPECT_EQ(*plan.run(0)[0], "[24, 32]");
  EXPECT_FALSE(plan.run(0)[1].has_value());
  EXPECT_EQ(*plan.run(1)[1], "0.9");
}

TEST(BatchPlan, MistakesNameTheFileAndTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {"[product]\nx = []\n", "product.x: the list is empty"},
      {"[product]\nx = 3\n", "product.x: expected a list"},
      {"duratoin = 2\n[product]\nx = [1]\n", "unknown field 'duratoin'"},
      {"duration = -1\n[product]\nx = [1]\n", "'duration' must be a positive"},
      {"[product]\nx = [1]\n[[runs]]\nx = 2\n", "not both"},
      {"duration = 1\n", "no runs"},
      {"[product]\nscene = [\"a\"]\n", "product.scene"},
      {"[product\n", "invalid TOML"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find("plan.toml"), std::string::npos) << text << " -> " << error;
    EXPECT_NE(error.find(expected), std::string::npos) << text << " -> " << error;
  }
}

// Every run's configuration is resolved before anything runs: a bad key or value is exit 2 naming
// the plan, the run and the field, and nothing is written.
TEST(BatchCli, BadOverridesAreRefusedBeforeAnythingRuns) {
  const fs::path dir = cli::fresh_scratch_dir("batch_bad");
  const std::pair<std::string, std::string> cases[] = {
      {"[product]\n\"jellyfish.frequency\" = [0.5, 9.0]\n", "jellyfish.frequency"},
      {"[product]\n\"jellyfish.frequncy\" = [0.5]\n", "jellyfish.frequncy"},
      {"scene = \"missing.toml\"\n[product]\n\"jellyfish.frequency\" = [0.5]\n", "missing.toml"},
  };
  for (const auto& [text, field] : cases) {
    const fs::path plan = write_plan(dir, text);
    const cli::CliResult r = cli::run_jellysim("batch " + plan.string() + " --quiet --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("plan.toml"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(field), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << text;
  }
  fs::remove_all(dir);
}

// batch.csv: a row per run in run order, the overrides then the figures, no wall-clock figure; each
// run's directory is what `simulate` writes; the same bytes on one thread and on two.
TEST(BatchCli, ThreadedBatchWritesOneRowPerRun) {
  const fs::path dir = cli::fresh_scratch_dir("batch_threads");
  const fs::path plan =
      write_plan(dir, std::string(kQuick) + "[product]\n\"jellyfish.frequency\" = [0.5, 0.9]\n\"jellyfish.gamma\" = [0.5, 0.6]\n");
  const cli::CliResult one = cli::run_jellysim("batch " + plan.string() + " --threads 1 --out " + (dir / "one").string());
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(one.output.find("4 runs"), std::string::npos) << one.output;
  const std::vector<std::string> rows = lines_of(cli::read_text_file(dir / "one" / "batch.csv"));
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0],
            "run,jellyfish.frequency,jellyfish.gamma,distance_travelled,distance_in_bell_heights,lateral_drift,"
            "mean_speed,cycles,volume_frequency,min_volume_ratio,min_aperture_ratio,daniel_distance,simulated_seconds,"
            "steps,smallest_step,largest_step,frames,failed");
  EXPECT_TRUE(rows[1].starts_with("0,0.5,0.5,")) << rows[1];
  EXPECT_TRUE(rows[2].starts_with("1,0.5,0.6,")) << rows[2];
  EXPECT_TRUE(rows[4].starts_with("3,0.9,0.6,")) << rows[4];
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_TRUE(rows[k].ends_with(",false")) << rows[k];
  EXPECT_EQ(cli::read_text_file(dir / "one" / "batch.csv").find("wall"), std::string::npos);
  const std::string summary = cli::read_text_file(dir / "one" / "runs" / "0003" / "summary.json");
  EXPECT_NE(summary.find("\"command\": \"simulate\""), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "one" / "runs" / "0003" / "metrics.csv"));
  EXPECT_EQ(lines_of(cli::read_text_file(dir / "one" / "batch_timings.csv")).front(), "run,rank,wall_seconds,resumed");

  const cli::CliResult two = cli::run_jellysim("batch " + plan.string() + " --quiet --threads 2 --out " + (dir / "two").string());
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_EQ(cli::read_text_file(dir / "two" / "batch.csv"), cli::read_text_file(dir / "one" / "batch.csv"));
  EXPECT_EQ(cli::read_text_file(dir / "two" / "runs" / "0002" / "metrics.csv"),
            cli::read_text_file(dir / "one" / "runs" / "0002" / "metrics.csv"));
  fs::remove_all(dir);
}

// A run whose simulation fails (exit 1 in `simulate`) is a row with failed = true; the batch goes on
// and exits 0, saying how many failed.
TEST(BatchCli, AFailingRunIsARowMarkedFailed) {
  const fs::path dir = cli::fresh_scratch_dir("batch_failing");
  const fs::path plan = write_plan(dir, std::string(kQuick) + "[[runs]]\n\"jellyfish.frequency\" = 0.7\n"
                                                              "[[runs]]\n\"stability.max_speed\" = 1e-9\n");
  const cli::CliResult r = cli::run_jellysim("batch " + plan.string() + " --quiet --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 of 2 runs failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("runs/0001 failed"), std::string::npos) << r.output;
  const std::vector<std::string> rows = lines_of(cli::read_text_file(dir / "out" / "batch.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[0].starts_with("run,jellyfish.frequency,stability.max_speed,")) << rows[0];
  EXPECT_TRUE(rows[1].starts_with("0,0.7,,")) << rows[1];
  EXPECT_TRUE(rows[1].ends_with(",false")) << rows[1];
  EXPECT_TRUE(rows[2].starts_with("1,,1e-09,")) << rows[2];
  EXPECT_TRUE(rows[2].ends_with(",true")) << rows[2];
  EXPECT_NE(cli::read_text_file(dir / "out" / "runs" / "0001" / "summary.json").find("\"status\": \"failed\""),
            std::string::npos);
  fs::remove_all(dir);
}

// A batch killed (SIGKILL) mid-way resumes: the same command completes only the runs not finished,
// and batch.csv is the one an uninterrupted batch writes.
TEST(BatchCli, AKilledBatchResumesOnlyTheMissingRuns) {
  const fs::path dir = cli::fresh_scratch_dir("batch_resume");
  // Two short runs, then two longer ones: the kill comes after the second run's summary.json.
  const fs::path plan = write_plan(dir, std::string(kQuick) + "[product]\nduration = [0.05, 0.5]\n"
                                                              "\"jellyfish.frequency\" = [0.5, 0.9]\n");
  const std::string command = std::string(JELLYSIM_CLI_PATH) + " batch " + plan.string() + " --quiet --threads 1 --out ";
  ASSERT_EQ(cli::run_jellysim("batch " + plan.string() + " --quiet --threads 1 --out " + (dir / "whole").string()).exit_code, 0);
  const fs::path out = dir / "killed";
  const std::string kill = "sh -c '" + command + out.string() + " & pid=$!; while [ ! -f " +
                           (out / "runs" / "0001" / "summary.json").string() +
                           " ]; do sleep 0.02; done; kill -9 $pid; wait $pid; exit 0'";
  ASSERT_EQ(std::system(kill.c_str()), 0);
  ASSERT_FALSE(fs::exists(out / "batch.csv"));
  const auto kept = fs::last_write_time(out / "runs" / "0000" / "summary.json");
  const cli::CliResult r = cli::run_jellysim("batch " + plan.string() + " --threads 1 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 run now, 2 resumed"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("runs/0000 done"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("runs/0003 done"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(out / "runs" / "0000" / "summary.json"), kept);
  EXPECT_EQ(cli::read_text_file(out / "batch.csv"), cli::read_text_file(dir / "whole" / "batch.csv"));
  // Run again: nothing is left to do.
  const cli::CliResult again = cli::run_jellysim("batch " + plan.string() + " --out " + out.string());
  EXPECT_NE(again.output.find("0 run now, 4 resumed"), std::string::npos) << again.output;
  // A directory holding anything else is refused, nothing touched.
  std::ofstream(out / "notes.txt") << "mine";
  const cli::CliResult refused = cli::run_jellysim("batch " + plan.string() + " --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("notes.txt"), std::string::npos) << refused.output;
  EXPECT_TRUE(fs::exists(out / "batch.csv"));
  fs::remove_all(dir);
}

namespace {

/// A sparse file of `bytes` (ftruncate: no disk used).
void sparse_file(const fs::path& file, off_t bytes) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, bytes), 0);
  ::close(fd);
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

// Issue 35 item 9: a plan is read like a scene file (a regular file of at most 1 MiB, its size
// checked before reading), so a 3 GB plan is refused at once; a product of 100 000 runs is
// validated by its values, not by materialising every run, and its runs are made when asked.
TEST(BatchPlan, AHugePlanIsRefusedAndALargeProductValidatedByItsValues) {
  const fs::path dir = cli::fresh_scratch_dir("batch_huge_plan");
  fs::create_directories(dir);
  sparse_file(dir / "plan.toml", off_t{3} << 30);
  const cli::CliResult r = cli::run_jellysim("batch " + (dir / "plan.toml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("plan.toml' is 3221225472 bytes; at most 1048576"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));

  // 10^5 runs; every value of every key is checked (here the last one of the third key is wrong).
  std::string text = std::string(kQuick) + "[product]\n";
  text += "\"jellyfish.frequency\" = [0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95]\n"
          "\"jellyfish.gamma\" = [0.5, 0.51, 0.52, 0.53, 0.54, 0.55, 0.56, 0.57, 0.58, 0.59]\n"
          "\"tank.density\" = [1000, 1001, 1002, 1003, 1004, 1005, 1006, 1007, 1008, 1009]\n"
          "\"tank.viscosity\" = [1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 7e-6, 8e-6, 9e-6, 1e-5]\n"
          "\"jellyfish.position\" = [[0.12, 0.080], [0.12, 0.081], [0.12, 0.082], [0.12, 0.083], [0.12, 0.084], "
          "[0.12, 0.085], [0.12, 0.086], [0.12, 0.087], [0.12, 0.088], [0.12, 0.089]]\n";
  const jellysim::experiments::Batch batch(parse_batch_plan(text, dir / "plan.toml"), {}, dir / "out");
  ASSERT_EQ(batch.size(), 100000u);
  EXPECT_EQ(batch.config(99999).to_json()["jellyfish"]["frequency"], 0.95);
  EXPECT_EQ(batch.config(12345).to_json()["tank"]["density"], 1003);
  try {
    const jellysim::experiments::Batch bad(parse_batch_plan(replace_all(text, "1e-5]", "-1]"), dir / "plan.toml"), {},
                                           dir / "out");
    ADD_FAILURE() << "a product with a value out of range was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tank.viscosity"), std::string::npos) << e.what();
  }
  // 1500 [[runs]]: each value checked once, in the first run that holds it.
  std::string listed = kQuick;
  for (int k = 0; k < 1500; ++k) listed += std::string("[[runs]]\n\"jellyfish.frequency\" = ") + (k % 2 ? "0.9\n" : "0.5\n");
  EXPECT_EQ(jellysim::experiments::Batch(parse_batch_plan(listed, dir / "plan.toml"), {}, dir / "out").size(), 1500u);
  try {
    const jellysim::experiments::Batch bad(parse_batch_plan(listed + "[[runs]]\n\"jellyfish.frequency\" = 9.0\n",
                                                            dir / "plan.toml"), {}, dir / "out");
    ADD_FAILURE() << "a list of runs with a value out of range was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("run 1500 (jellyfish.frequency=9)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

// Issue 35 item 5: a resumed batch takes a run as finished only when its summary.json is a regular
// file (never a pipe, a directory or a link) with every figure a number, and every file its
// manifest lists is there; anything else is redone. A symbolic link for runs/ or a run's directory
// is refused (exit 2): a batch writes only inside its --out.
TEST(BatchCli, AResumeRedoesRunsWhoseFilesAreNotWhatTheRunWrote) {
  const fs::path dir = cli::fresh_scratch_dir("batch_distrust");
  const fs::path plan = write_plan(dir, replace_all(kQuick, "duration = 0.1", "duration = 0.05") +
                                             "[product]\n\"jellyfish.frequency\" = [0.5, 0.7, 0.9]\n");
  const fs::path out = dir / "out";
  const std::string command = "batch " + plan.string() + " --threads 1 --out " + out.string();
  ASSERT_EQ(cli::run_jellysim(command + " --quiet").exit_code, 0);
  const std::string whole = cli::read_text_file(out / "batch.csv");
  const auto expect_resumed = [&](const std::string& counts) {
    const cli::CliResult r = cli::run_jellysim(command);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(counts), std::string::npos) << r.output;
    EXPECT_EQ(cli::read_text_file(out / "batch.csv"), whole);
  };
  const auto edit_summary = [&](const std::string& run, const auto& edit) {
    nlohmann::ordered_json summary = nlohmann::ordered_json::parse(cli::read_text_file(out / "runs" / run / "summary.json"));
    edit(summary);
    std::ofstream(out / "runs" / run / "summary.json") << summary.dump(2);
  };
  edit_summary("0000", [](auto& s) { s["distance_travelled"] = "abc"; });
  edit_summary("0001", [](auto& s) { s.erase("frames"); });
  fs::remove(out / "runs" / "0002" / "metrics.csv");
  expect_resumed("3 run now, 0 resumed");

  fs::remove(out / "runs" / "0000" / "summary.json");
  ASSERT_EQ(::mkfifo((out / "runs" / "0000" / "summary.json").c_str(), 0644), 0);  // once hung the batch
  fs::remove(out / "runs" / "0001" / "summary.json");
  fs::create_directory(out / "runs" / "0001" / "summary.json");  // once exit 1 naming no file
  expect_resumed("2 run now, 1 resumed");

  fs::rename(out / "runs" / "0002", dir / "elsewhere");
  fs::create_directory_symlink(dir / "elsewhere", out / "runs" / "0002");
  cli::CliResult r = cli::run_jellysim(command);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'runs/0002' is a symbolic link"), std::string::npos) << r.output;
  fs::remove(out / "runs" / "0002");
  fs::rename(out / "runs", dir / "runs_elsewhere");
  fs::create_directory_symlink(dir / "runs_elsewhere", out / "runs");
  r = cli::run_jellysim(command);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'runs' is a symbolic link"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "runs_elsewhere" / "0000" / "summary.json"));  // nothing touched
  fs::remove_all(dir);
}
