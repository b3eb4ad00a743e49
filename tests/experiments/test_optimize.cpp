// `jellysim optimize`'s plumbing (docs/control.md) on an analytic objective: the plan, NLopt, the
// constraints, evaluations.csv and its replay, through run_optimize with a cheap evaluator in
// place of the swim (the swim itself is tested end to end in tests/app/test_optimize_cli.cpp).
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/optimize.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace js = jellysim;
namespace fs = std::filesystem;
using js::experiments::Evaluation;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("jellysim_test_optimize_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A smooth hill with its top at frequency 0.9 Hz, contract_fraction 0.4; "peak_muscle_tension"
/// is the frequency itself (for the constraint test).
js::experiments::Evaluator hill(std::atomic<int>* calls = nullptr) {
  return [calls](const js::config::Config& c) {
    if (calls) ++*calls;
    const double f = c.number("jellyfish.frequency"), q = c.number("jellyfish.contract_fraction");
    Evaluation e;
    e.figures["distance_per_cycle"] = 0.03 - (f - 0.9) * (f - 0.9) - 0.5 * (q - 0.4) * (q - 0.4);
    e.figures["peak_muscle_tension"] = f;
    return e;
  };
}

js::experiments::OptimizePlan plan(const std::string& algorithm, int evaluations, const std::string& extra = "") {
  return js::experiments::parse_optimize_plan(
      "cycles = 3\nobjective = \"distance_per_cycle\"\nsense = \"maximize\"\nalgorithm = \"" + algorithm +
          "\"\nevaluations = " + std::to_string(evaluations) +
          "\nseed = 3\n[variables]\n\"jellyfish.frequency\" = [0.3, 1.5]\n\"jellyfish.contract_fraction\" = [0.15, 0.6]\n" +
          extra,
      "plan.toml");
}

}  // namespace

TEST(Optimize, LocalAndGlobalAlgorithmsFindTheHillTop) {
  for (const std::string algorithm : {"bobyqa", "sbplx", "crs2_lm"}) {
    const fs::path dir = scratch("hill_" + algorithm);
    const auto s = js::experiments::run_optimize(plan(algorithm, algorithm == "crs2_lm" ? 150 : 60), dir, true, hill());
    EXPECT_NEAR(s["best_variables"]["jellyfish.frequency"].get<double>(), 0.9, 0.02) << algorithm;
    EXPECT_NEAR(s["best_variables"]["jellyfish.contract_fraction"].get<double>(), 0.4, 0.04) << algorithm;
    EXPECT_GT(s["best_objective"].get<double>(), s["baseline_objective"].get<double>()) << algorithm;
    EXPECT_LE(s["evaluations"].get<int>(), algorithm == "crs2_lm" ? 150 : 60);
    for (const char* file : {"evaluations.csv", "best.toml", "progress.png", "summary.json"})
      EXPECT_TRUE(fs::exists(dir / file)) << algorithm << " " << file;
    fs::remove_all(dir);
  }
}

TEST(Optimize, ConstraintsHoldTheOptimumAtTheirBound) {
  // The top is at f = 0.9; the constraint f <= 0.7 moves it to the bound, natively (cobyla) or by
  // the penalty (bobyqa).
  for (const std::string algorithm : {"cobyla", "bobyqa"}) {
    const fs::path dir = scratch("constrained_" + algorithm);
    const auto s = js::experiments::run_optimize(
        plan(algorithm, 80, "[constraints]\npeak_muscle_tension = [0.0, 0.7]\n"), dir, true, hill());
    EXPECT_NEAR(s["best_variables"]["jellyfish.frequency"].get<double>(), 0.7, 0.02) << algorithm;
    EXPECT_LE(s["best_variables"]["jellyfish.frequency"].get<double>(), 0.7) << algorithm;
    EXPECT_TRUE(s["best_feasible"].get<bool>());
    fs::remove_all(dir);
  }
}

TEST(Optimize, ResumeReplaysTheEarlierEvaluationsAndWritesTheSameFile) {
  const fs::path whole = scratch("whole"), cut = scratch("cut");
  js::experiments::run_optimize(plan("cobyla", 20), whole, true, hill());
  const std::string expected = read(whole / "evaluations.csv");
  // A run killed after six evaluations: its directory with evaluations.csv cut there.
  fs::copy(whole, cut, fs::copy_options::recursive);
  std::istringstream lines(expected);
  std::string kept, line;
  for (int k = 0; k < 7 && std::getline(lines, line); ++k) kept += line + "\n";
  std::ofstream(cut / "evaluations.csv", std::ios::binary) << kept << "3,0.5";  // and a line cut short
  std::atomic<int> calls{0};
  const auto s = js::experiments::run_optimize(plan("cobyla", 20), cut, true, hill(&calls));
  EXPECT_EQ(read(cut / "evaluations.csv"), expected);
  EXPECT_EQ(s["replayed_evaluations"].get<int>(), 6);
  EXPECT_EQ(calls.load() + 6, s["evaluations"].get<int>());
  fs::remove_all(whole);
  fs::remove_all(cut);
}

TEST(Optimize, FailedEvaluationsAreRecordedWithAPenalty) {
  const fs::path dir = scratch("failing");
  const auto failing = [](const js::config::Config& c) {
    Evaluation e = hill()(c);
    e.failed = c.number("jellyfish.frequency") > 1.2;  // a "blow-up" at high frequencies
    if (e.failed) e.figures.clear();
    return e;
  };
  const auto s = js::experiments::run_optimize(plan("crs2_lm", 60), dir, true, failing);
  EXPECT_GT(s["failed_evaluations"].get<int>(), 0);
  EXPECT_LE(s["best_variables"]["jellyfish.frequency"].get<double>(), 1.2);
  EXPECT_NE(read(dir / "evaluations.csv").find(",1\n"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Optimize, ThePlanIsCheckedFieldByField) {
  const auto error = [](const std::string& text) {
    try {
      js::experiments::parse_optimize_plan(text, "p.toml");
    } catch (const js::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string vars = "[variables]\n\"jellyfish.frequency\" = [0.3, 1.5]\n";
  EXPECT_NE(error("cycles = 3\nobjective = \"fastest\"\n" + vars).find("field 'objective' must be one of"), std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"speed\"\nalgorithm = \"lbfgs\"\n" + vars).find("p.toml:3: field 'algorithm'"),
            std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"speed\"\nevaluations = 0\n" + vars).find("[1, 100000]"), std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"speed\"\n[variables]\n\"jellyfish.frequency\" = [1.5, 0.3]\n")
                .find("variables.jellyfish.frequency"),
            std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"speed\"\n" + vars + "[constraints]\nbeauty = [0, 1]\n").find("unknown figure"),
            std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"reach\"\n" + vars).find("[target]"), std::string::npos);
  EXPECT_NE(error("objective = \"speed\"\n" + vars).find("'cycles'"), std::string::npos);
  EXPECT_NE(error("cycles = 3\nobjective = \"speed\"\ncolour = 1\n" + vars).find("unknown field 'colour'"), std::string::npos);
}

TEST(Optimize, TwoObjectivesWriteTheParetoFront) {
  const fs::path dir = scratch("pareto");
  const auto plan2 = js::experiments::parse_optimize_plan(
      "cycles = 3\nobjectives = [\"speed\", \"cost_of_transport\"]\nalgorithm = \"cobyla\"\nevaluations = 30\n"
      "pareto_points = 3\nthreads = 2\n[variables]\n\"jellyfish.frequency\" = [0.3, 1.5]\n"
      "\"jellyfish.contract_fraction\" = [0.15, 0.6]\n",
      "plan.toml");
  // speed rises with the frequency, the cost too: a trade-off along f.
  const auto tradeoff = [](const js::config::Config& c) {
    const double f = c.number("jellyfish.frequency"), q = c.number("jellyfish.contract_fraction");
    Evaluation e;
    e.figures["speed"] = f * (1.0 - (q - 0.4) * (q - 0.4));
    e.figures["cost_of_transport"] = 0.2 + f * f;
    return e;
  };
  const auto s = js::experiments::run_optimize(plan2, dir, true, tradeoff);
  EXPECT_GE(s["pareto_points"].get<int>(), 2);
  for (const char* file : {"evaluations.csv", "pareto.csv", "pareto.png", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  const std::string first = read(dir / "evaluations.csv");
  // The same bytes on one thread.
  const fs::path one = scratch("pareto_one");
  auto serial = plan2;
  serial.threads = 1;
  js::experiments::run_optimize(serial, one, true, tradeoff);
  EXPECT_EQ(read(one / "evaluations.csv"), first);
  fs::remove_all(dir);
  fs::remove_all(one);
}
