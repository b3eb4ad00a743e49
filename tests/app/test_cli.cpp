// End-to-end checks of the jellysim command line: exit codes, error messages, outputs, determinism.
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

Result jellysim(const std::string& args) {
  const std::string cmd = std::string(JELLYSIM_CLI_PATH) + " " + args + " 2>&1";
  Result r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe) != nullptr) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("jellysim_cli_" + name);
  fs::remove_all(dir);
  return dir;
}

nlohmann::json summary_of(const fs::path& dir) { return nlohmann::json::parse(read_file(dir / "summary.json")); }

}  // namespace

TEST(Cli, HelpDocumentsCommands) {
  const Result r = jellysim("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* word : {"run", "experiment", "scenes"}) EXPECT_NE(r.output.find(word), std::string::npos) << word;
  const Result sub = jellysim("run --help");
  EXPECT_EQ(sub.exit_code, 0);
  for (const char* word : {"--out", "--set", "--duration"}) EXPECT_NE(sub.output.find(word), std::string::npos);
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(jellysim("").exit_code, 2);
  EXPECT_EQ(jellysim("frobnicate").exit_code, 2);
  const Result r = jellysim("experiment no-such-thing --out " + fresh_dir("unknown").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("swinging-bar"), std::string::npos) << r.output;  // lists known names
}

TEST(Cli, BadSetValueNamesFieldAndLeavesNoOutput) {
  const fs::path dir = fresh_dir("bad_set");
  Result r = jellysim("run --quiet --out " + dir.string() + " --set bar.point_mass=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.point_mass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("out of range"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
  r = jellysim("run --quiet --out " + dir.string() + " --set time.integrator=rk7");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("dopri5"), std::string::npos) << r.output;  // lists the allowed values
  r = jellysim("run --quiet --out " + dir.string() + " --duration -3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("duration"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(Cli, BadSceneFileNamesFieldAndLeavesNoOutput) {
  const fs::path dir = fresh_dir("bad_scene");
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar]\nsegmnets = 4\n";
  Result r = jellysim("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.segmnets"), std::string::npos) << r.output;
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar]\nsegments = \"many\"\n";
  r = jellysim("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.segments"), std::string::npos) << r.output;
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar\n";
  r = jellysim("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("scene.toml:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(Cli, SwingingBarWritesItsOutputs) {
  const fs::path dir = fresh_dir("bar");
  const Result r = jellysim("experiment swinging-bar --quiet --duration 4 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"frames.csv", "energy.csv", "energy.png", "swinging_bar.png", "summary.json"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  const auto summary = summary_of(dir);
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_DOUBLE_EQ(summary["simulated_seconds"].get<double>(), 4.0);
  EXPECT_EQ(summary["steps"].get<int>(), 400);  // fixed dt = 0.01
  EXPECT_EQ(summary["config"]["bar"]["point_mass"].get<double>(), 24.0);
  EXPECT_EQ(read_file(dir / "frames.csv").substr(0, 15), "frame,t,point,x");
  // 17 frames (t = 0, 0.25, ..., 4) of 22 points, plus the header.
  const std::string frames = read_file(dir / "frames.csv");
  EXPECT_EQ(std::count(frames.begin(), frames.end(), '\n'), 1 + 17 * 22);
  fs::remove_all(dir);
}

TEST(Cli, SameInputsGiveByteIdenticalOutputs) {
  const fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
  const std::string args = "run --quiet --duration 3 --set time.adaptive=true --set time.integrator=rk4 --out ";
  ASSERT_EQ(jellysim(args + a.string()).exit_code, 0);
  ASSERT_EQ(jellysim(args + b.string()).exit_code, 0);
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(a)) {
    const std::string name = entry.path().filename().string();
    if (name == "summary.json") {
      auto sa = summary_of(a), sb = summary_of(b);
      sa.erase("wall_seconds");  // the only field allowed to differ
      sb.erase("wall_seconds");
      EXPECT_EQ(sa, sb);
    } else {
      EXPECT_EQ(read_file(entry.path()), read_file(b / name)) << name;
    }
    ++compared;
  }
  EXPECT_GE(compared, 5);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Cli, DivergingRunStopsWithWhenAndWhereAndKeepsResults) {
  const fs::path dir = fresh_dir("diverge");
  const Result r = jellysim("run --quiet --duration 50 --set time.integrator=forward-euler --set time.dt=0.2 --out " +
                            dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("diverged at t ="), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("point"), std::string::npos) << r.output;
  const auto summary = summary_of(dir);
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_LT(summary["simulated_seconds"].get<double>(), 50.0);
  EXPECT_TRUE(fs::exists(dir / "frames.csv"));
  fs::remove_all(dir);
}

TEST(Cli, IntegratorOrderExperimentMeasuresExpectedOrders) {
  const fs::path dir = fresh_dir("order");
  const Result r = jellysim("experiment integrator-order --quiet --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto orders = summary_of(dir)["measured_orders"];
  const std::map<std::string, double> expected = {{"forward-euler", 1}, {"predictor-corrector", 1}, {"leapfrog", 2},
                                                  {"rk2", 2}, {"rk4", 4}, {"dopri5", 5}, {"backward-euler", 1}};
  for (const auto& [name, order] : expected) {
    ASSERT_TRUE(orders.contains(name)) << name;
    EXPECT_NEAR(orders[name].get<double>(), order, 0.3) << name;
  }
  EXPECT_TRUE(fs::exists(dir / "integrator_order.png"));
  EXPECT_TRUE(fs::exists(dir / "convergence.csv"));
  fs::remove_all(dir);
}

TEST(Cli, DrivenCavityWritesProfilesAndGhiaComparison) {
  const fs::path dir = fresh_dir("cavity");
  const Result r = jellysim("experiment driven-cavity --quiet --solver eulerian --re 100 --grid 16 "
                            "--set figure_8_7.enabled=false --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_file(dir / "centerline_u.csv").substr(0, 4), "y,u\n");
  EXPECT_EQ(read_file(dir / "centerline_v.csv").substr(0, 4), "x,v\n");
  for (const char* f : {"ghia_comparison.csv", "cavity_speed.png", "cavity_vorticity.png", "cavity.vti", "cavity.pvd",
                        "frames/field_000000.vti", "frames/tracers_000000.vtp"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  // The time series lists a field and a tracer file per frame, each of which exists.
  const std::string pvd = read_file(dir / "cavity.pvd");
  int listed = 0;
  for (auto pos = pvd.find("file=\""); pos != std::string::npos; pos = pvd.find("file=\"", pos + 1), ++listed) {
    const auto start = pos + 6;
    EXPECT_TRUE(fs::exists(dir / pvd.substr(start, pvd.find('"', start) - start)));
  }
  EXPECT_GE(listed, 2 * 5);  // at least five frames at the default interval of 1 s
  const auto summary = summary_of(dir);
  EXPECT_EQ(summary["config"]["grid"].get<int>(), 16);
  // A 16² grid is coarse: the profiles are qualitatively right, within 0.1 of Ghia et al.
  // (the 0.02 check at 64² is in tests/fluid).
  EXPECT_LT(summary["ghia_max_abs_u_error"].get<double>(), 0.1);
  EXPECT_LT(summary["ghia_max_abs_v_error"].get<double>(), 0.1);
  EXPECT_EQ(jellysim("experiment driven-cavity --quiet --solver rk4 --out " + dir.string() + "_bad").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir.string() + "_bad"));
  fs::remove_all(dir);
}

TEST(Cli, TaylorGreenMeasuresSpatialOrderOfBothSolvers) {
  const fs::path dir = fresh_dir("taylor_green");
  const Result r = jellysim("experiment taylor-green --quiet --set 'study.grids=[16, 32, 64]' --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto orders = summary_of(dir)["measured_orders_l2"];
  EXPECT_GT(orders["eulerian"].get<double>(), 1.7);        // second order in space
  EXPECT_NEAR(orders["semi-lagrangian"].get<double>(), 0.9, 0.2);  // first order (splitting, Δt ∝ Δx)
  EXPECT_EQ(read_file(dir / "taylor_green.csv").substr(0, 16), "solver,cells,dx,");
  EXPECT_TRUE(fs::exists(dir / "taylor_green.png"));
  fs::remove_all(dir);
}

TEST(Cli, SolverCostTablesEveryCombination) {
  const fs::path dir = fresh_dir("solver_cost");
  const Result r = jellysim("experiment solver-cost --quiet --set 'study.grids=[16, 32]' --set study.steps=2 --out " +
                            dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string csv = read_file(dir / "solver_cost.csv");
  EXPECT_EQ(csv.substr(0, 29), "solver,pressure_solver,cells,");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 2 * 2);  // solvers x pressure solvers x grids
  EXPECT_NE(csv.find("semi-lagrangian,multigrid,32,"), std::string::npos);
  const Result bad = jellysim("experiment solver-cost --quiet --set 'study.pressure_solvers=[\"jacobi\"]' --out " +
                              dir.string() + "_bad");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("study.pressure_solvers"), std::string::npos) << bad.output;
  fs::remove_all(dir);
}
