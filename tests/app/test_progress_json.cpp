// `--progress json` (issue 38, docs/cli.md): every long command writes one JSON object per line on
// stderr (stage, time, duration, fraction, steps, eta_seconds), throttled, then a status line; the
// tracker's throttle and ETA; a bad input's status line.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_runner.hpp"
#include "jellysim/experiments/progress.hpp"

namespace {

namespace fs = std::filesystem;
namespace cli = jellysim::testing;
using nlohmann::json;

/// A tiny jellyfish run: a coarse grid, no pictures.
const std::string kTiny = " --set tank.cells=[48,64] --set output.pictures=false";

/// Runs `jellysim ARGS --progress json` and keeps its stderr only (stdout discarded).
cli::CliResult run_for_stderr(const std::string& args) {
  return cli::run_command(std::string(JELLYSIM_CLI_PATH) + " " + args + " --progress json 2>&1 >/dev/null");
}

/// Every stderr line of `jellysim ARGS --progress json` but the human-readable error must be a JSON object.
std::vector<json> progress_lines(const std::string& args, int expected_exit = 0) {
  const cli::CliResult r = run_for_stderr(args);
  EXPECT_EQ(r.exit_code, expected_exit) << args << "\n" << r.output;
  std::vector<json> lines;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("jellysim:", 0) == 0) continue;  // the human-readable error beside the status
    try {
      lines.push_back(json::parse(line));
    } catch (const json::parse_error& e) {
      ADD_FAILURE() << args << ": not JSON: " << line;
    }
  }
  return lines;
}

/// The stage lines are well formed (fraction in [0, 1], non-decreasing within a stage's run) and
/// the last line is the status.
void expect_well_formed(const std::vector<json>& lines, const std::string& stage, const std::string& status, int code) {
  ASSERT_GE(lines.size(), 2u);
  int stage_lines = 0;
  for (std::size_t k = 0; k + 1 < lines.size(); ++k) {
    const json& l = lines[k];
    ASSERT_TRUE(l.contains("stage")) << l;
    ASSERT_TRUE(l.contains("fraction") && l.contains("eta_seconds")) << l;
    EXPECT_GE(l["fraction"].get<double>(), 0.0);
    EXPECT_LE(l["fraction"].get<double>(), 1.0);
    if (l["stage"] == stage) ++stage_lines;
    if (l["stage"] == "simulate") {
      for (const char* key : {"time", "duration", "steps"}) EXPECT_TRUE(l.contains(key)) << key << " in " << l;
    }
  }
  EXPECT_GE(stage_lines, 1) << "no '" << stage << "' line";
  int status_lines = 0;
  for (const json& l : lines) status_lines += l.contains("status") ? 1 : 0;
  EXPECT_EQ(status_lines, 1);
  const json& last = lines.back();
  EXPECT_EQ(last["status"], status) << last;
  EXPECT_EQ(last["exit_code"], code) << last;
  EXPECT_TRUE(last.contains("out") && last.contains("message")) << last;
}

TEST(ProgressJson, SimulateWritesParsableLinesAndADoneStatus) {
  const fs::path dir = cli::fresh_scratch_dir("progress_simulate");
  const auto lines = progress_lines("simulate --duration 0.1" + kTiny + " --out " + dir.string());
  expect_well_formed(lines, "simulate", "done", 0);
  ASSERT_GE(lines.size(), 2u);
  const json& last_stage = lines[lines.size() - 2];
  EXPECT_EQ(last_stage["fraction"], 1.0) << last_stage;  // the last report always gets through
  EXPECT_EQ(last_stage["eta_seconds"], 0.0) << last_stage;
  EXPECT_NE(lines.back()["out"].get<std::string>().find(dir.string()), std::string::npos);
  fs::remove_all(dir);
}

// `run` reports its render stage too: frames done of all.
TEST(ProgressJson, RunReportsTheRenderStage) {
  const fs::path dir = cli::fresh_scratch_dir("progress_run");
  const auto lines = progress_lines("run --duration 0.1" + kTiny +
                                    " --set render.width=64 --set render.height=64 --set render.video=false --out " +
                                    dir.string());
  expect_well_formed(lines, "render", "done", 0);
  bool render_done = false;
  for (const json& l : lines)
    if (l.value("stage", "") == "render" && l["fraction"] == 1.0)
      render_done = l["frames"] == l["frames_total"] && l["frames_total"].get<int>() > 0;
  EXPECT_TRUE(render_done);
  fs::remove_all(dir);
}

TEST(ProgressJson, ExperimentWritesParsableLines) {
  const fs::path dir = cli::fresh_scratch_dir("progress_experiment");
  const auto lines = progress_lines("experiment swinging-bar --duration 0.5 --out " + dir.string());
  expect_well_formed(lines, "simulate", "done", 0);
  fs::remove_all(dir);
}

TEST(ProgressJson, BatchCountsItsRuns) {
  const fs::path dir = cli::fresh_scratch_dir("progress_batch");
  fs::create_directories(dir);
  const fs::path plan = dir / "plan.toml";
  std::ofstream(plan) << "duration = 0.1\n[set]\n\"tank.cells\" = [48, 64]\n\"output.pictures\" = false\n"
                         "[product]\n\"jellyfish.frequency\" = [0.5, 0.9]\n";
  const auto lines = progress_lines("batch " + plan.string() + " --threads 1 --out " + (dir / "out").string());
  expect_well_formed(lines, "batch", "done", 0);
  EXPECT_EQ(lines[lines.size() - 2]["runs"], 2) << lines[lines.size() - 2];
  fs::remove_all(dir);
}

TEST(ProgressJson, OptimizeCountsItsEvaluations) {
  const fs::path dir = cli::fresh_scratch_dir("progress_optimize");
  fs::create_directories(dir);
  const fs::path plan = dir / "plan.toml";
  std::ofstream(plan) << "cycles = 2\nobjective = \"distance_per_cycle\"\nalgorithm = \"cobyla\"\nevaluations = 3\n"
                         "[set]\n\"tank.cells\" = [48, 64]\n\"jellyfish.frequency\" = 3.0\n"
                         "[variables]\n\"jellyfish.frequency\" = [2.5, 3.5]\n";
  const auto lines = progress_lines("optimize " + plan.string() + " --out " + (dir / "out").string());
  expect_well_formed(lines, "optimize", "done", 0);
  const json& last_count = lines[lines.size() - 2];
  EXPECT_EQ(last_count["evaluations_total"], 3) << last_count;
  EXPECT_GE(last_count["evaluations"].get<int>(), 1) << last_count;
  fs::remove_all(dir);
}

// A bad input is exit 2 and a "failed" status line whose message names the field.
TEST(ProgressJson, BadInputEndsWithAFailedStatus) {
  const fs::path dir = cli::fresh_scratch_dir("progress_bad");
  const auto lines = progress_lines("simulate --set jellyfish.frequency=-1 --out " + dir.string(), 2);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back()["status"], "failed");
  EXPECT_EQ(lines.back()["exit_code"], 2);
  EXPECT_NE(lines.back()["message"].get<std::string>().find("jellyfish.frequency"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ProgressJson, AnUnknownModeIsRefused) {
  const cli::CliResult r = cli::run_jellysim("simulate --progress xml");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--progress"), std::string::npos) << r.output;
}

// At most one line per 0.2 s, plus the last (fraction 1), whatever the rate of reports.
TEST(ProgressTracker, ThrottlesButLetsTheLastThrough) {
  jellysim::experiments::ProgressTracker tracker("simulate");
  int admitted = 0;
  for (int k = 0; k <= 1000; ++k)
    if (!tracker.simulation(0.001 * k, 1.0, k).is_null()) ++admitted;
  EXPECT_EQ(admitted, 2);  // the first and the last, in far less than 0.2 s
  const auto status = jellysim::experiments::progress_status(130, "out/x", "interrupted by SIGINT");
  EXPECT_EQ(status["status"], "interrupted");
  EXPECT_EQ(jellysim::experiments::progress_status(1, "o", "m")["status"], "failed");
  EXPECT_EQ(jellysim::experiments::progress_status(0, "o", "m")["status"], "done");
}

TEST(ProgressTracker, EstimatesTheTimeLeftFromTheRate) {
  jellysim::experiments::ProgressTracker tracker("render", 0.0);
  EXPECT_TRUE(tracker.count(0, 10, "frames")["eta_seconds"].is_null());  // nothing moved yet
  const auto line = tracker.count(5, 10, "frames");
  ASSERT_FALSE(line.is_null());
  EXPECT_GE(line["eta_seconds"].get<double>(), 0.0);
  EXPECT_EQ(line["frames"], 5);
  EXPECT_EQ(line["frames_total"], 10);
  EXPECT_EQ(line["fraction"], 0.5);
}

}  // namespace
