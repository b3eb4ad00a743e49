// `jellysim batch` (docs/batch.md): the plan's reading and validation, the threaded backend's
// batch.csv, a failing run's row, and resuming a killed batch. The MPI backend's byte-for-byte
// comparison with the threaded one is tests/app/batch_mpi_test.sh (registered when MPI is built).
#include <gtest/gtest.h>

#include "../cli_runner.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/batch.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

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
  ASSERT_EQ(plan.runs.size(), 6u);
  EXPECT_EQ(*plan.runs[0][0], "0.5");
  EXPECT_EQ(*plan.runs[0][1], "0.5");
  EXPECT_EQ(*plan.runs[1][1], "0.6");
  EXPECT_EQ(*plan.runs[2][0], "0.7");
  EXPECT_EQ(*plan.runs[5][0], "0.9");
  EXPECT_EQ(*plan.runs[5][2], "\"fft\"");
}

// [[runs]]: one run per table, the columns in order of first appearance, absent keys left to the scene.
TEST(BatchPlan, RunsListTakesEachTableAsARun) {
  const auto plan = parse_batch_plan(
      "[set]\n\"output.vtk\" = false\n[[runs]]\n\"tank.cells\" = [24, 32]\n[[runs]]\njellyfish.frequency = 0.9\n"
      "\"tank.cells\" = [48, 64]\n",
      "p.toml");
  EXPECT_EQ(plan.shared, std::vector<std::string>{"output.vtk=false"});
  EXPECT_EQ(plan.keys, (std::vector<std::string>{"tank.cells", "jellyfish.frequency"}));
  ASSERT_EQ(plan.runs.size(), 2u);
  EXPECT_EQ(*plan.runs[0][0], "[24, 32]");
  EXPECT_FALSE(plan.runs[0][1].has_value());
  EXPECT_EQ(*plan.runs[1][1], "0.9");
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
