// `jellysim optimize` end to end on a coarse tank (48 x 96 cells, two cycles: a third of a second
// an evaluation): best.toml reproduces its evaluation under `jellysim simulate` to the bit, a
// killed run resumes to the same evaluations.csv, bad plans are exit 2 naming the field with
// nothing written (docs/control.md).
#include "../cli_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <thread>

namespace fs = std::filesystem;
using jellysim::testing::fresh_scratch_dir;
using jellysim::testing::read_text_file;
using jellysim::testing::run_jellysim;

namespace {

const std::string kCoarsePlan =
    "cycles = 2\nobjective = \"distance_per_cycle\"\nsense = \"maximize\"\nalgorithm = \"cobyla\"\n"
    "evaluations = 5\nseed = 1\n[set]\n\"tank.cells\" = [48, 96]\n[variables]\n"
    "\"jellyfish.frequency\" = [0.5, 1.2]\n\"jellyfish.contract_fraction\" = [0.15, 0.6]\n"
    "[constraints]\ndistance_travelled = [-inf, inf]\npeak_muscle_tension = [0.0, 10.0]\n";

fs::path write_plan(const fs::path& dir, const std::string& text) {
  fs::create_directories(dir);
  std::ofstream(dir / "plan.toml") << text;
  return dir / "plan.toml";
}

/// The cells of evaluations.csv's row `evaluation` under `column`.
std::string cell(const std::string& csv, int evaluation, const std::string& column) {
  std::istringstream lines(csv);
  std::string header, line;
  std::getline(lines, header);
  std::vector<std::string> names, cells;
  std::stringstream h(header);
  for (std::string c; std::getline(h, c, ',');) names.push_back(c);
  while (std::getline(lines, line)) {
    cells.clear();
    std::stringstream l(line);
    for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
    if (cells[0] == std::to_string(evaluation))
      for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == column) return cells[i];
  }
  return "";
}

}  // namespace

TEST(OptimizeCli, BestTomlReproducesTheBestEvaluationUnderSimulate) {
  const fs::path dir = fresh_scratch_dir("optimize_best");
  const fs::path plan = write_plan(dir, kCoarsePlan);
  const auto r = run_jellysim("optimize " + plan.string() + " --out " + (dir / "out").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = nlohmann::json::parse(read_text_file(dir / "out/summary.json"));
  EXPECT_EQ(summary["evaluations"].get<int>(), 5);
  for (const char* key : {"best_objective", "baseline_objective", "best_variables", "evaluations", "wall_seconds"})
    EXPECT_TRUE(summary.contains(key)) << key;
  const int best = summary["best_evaluation"].get<int>();
  const auto s = run_jellysim("simulate " + (dir / "out/best.toml").string() + " --out " + (dir / "sim").string() + " --quiet");
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const auto sim = nlohmann::json::parse(read_text_file(dir / "sim/summary.json"));
  const std::string csv = read_text_file(dir / "out/evaluations.csv");
  EXPECT_EQ(std::strtod(cell(csv, best, "distance_travelled").c_str(), nullptr), sim["distance_travelled"].get<double>());
  fs::remove_all(dir);
}

TEST(OptimizeCli, AKilledRunResumesToTheSameEvaluations) {
  const fs::path dir = fresh_scratch_dir("optimize_resume");
  std::string text = kCoarsePlan;
  text.replace(text.find("evaluations = 5"), 15, "evaluations = 8");
  const fs::path plan = write_plan(dir, text);
  ASSERT_EQ(run_jellysim("optimize " + plan.string() + " --out " + (dir / "whole").string() + " --quiet").exit_code, 0);
  const pid_t pid = jellysim::testing::spawn_jellysim({"optimize", plan.string(), "--out", (dir / "cut").string()});
  ASSERT_GT(pid, 0);
  for (int k = 0; k < 600; ++k) {  // kill it once it has three evaluations
    const std::string csv = read_text_file(dir / "cut/evaluations.csv");
    if (std::count(csv.begin(), csv.end(), '\n') >= 4) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  const auto r = run_jellysim("optimize " + plan.string() + " --out " + (dir / "cut").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text_file(dir / "cut/evaluations.csv"), read_text_file(dir / "whole/evaluations.csv"));
  const auto summary = nlohmann::json::parse(read_text_file(dir / "cut/summary.json"));
  EXPECT_GE(summary["replayed_evaluations"].get<int>(), 3);
  fs::remove_all(dir);
}

TEST(OptimizeCli, BadPlansAreExit2NamingTheFieldWithNothingWritten) {
  const fs::path dir = fresh_scratch_dir("optimize_bad");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"evaluations = 5", "evaluations = -3"},
      {"algorithm = \"cobyla\"", "algorithm = \"simplex\""},
      {"\"jellyfish.frequency\" = [0.5, 1.2]", "\"jellyfish.frequency\" = [0.5, 9.0]"},
      {"\"jellyfish.frequency\" = [0.5, 1.2]", "\"jellyfish.colour\" = [0.5, 1.2]"},
      {"peak_muscle_tension = [0.0, 10.0]", "peak_muscle_tension = [10.0, 0.0]"},
  };
  const std::vector<std::string> named = {"evaluations' must be an integer in [1, 100000]", "field 'algorithm'",
                                          "jellyfish.frequency", "jellyfish.colour", "constraints.peak_muscle_tension"};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    std::string text = kCoarsePlan;
    text.replace(text.find(cases[k].first), cases[k].first.size(), cases[k].second);
    const fs::path plan = write_plan(dir, text);
    const auto r = run_jellysim("optimize " + plan.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(named[k]), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << cases[k].second;
  }
  fs::remove_all(dir);
}

TEST(OptimizeCli, TwoObjectivesWriteParetoFiles) {
  const fs::path dir = fresh_scratch_dir("optimize_pareto");
  std::string text = kCoarsePlan;
  text.replace(text.find("objective = \"distance_per_cycle\"\nsense = \"maximize\""), 51,
               "objectives = [\"speed\", \"cost_of_transport\"]\npareto_points = 2");
  const fs::path plan = write_plan(dir, text);
  const auto r = run_jellysim("optimize " + plan.string() + " --out " + (dir / "out").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"evaluations.csv", "pareto.csv", "pareto.png", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  fs::remove_all(dir);
}
