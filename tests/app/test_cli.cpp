// End-to-end checks of the jellysim command line: exit codes, error messages, outputs, determinism.
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>

#include "../cli_runner.hpp"

namespace cli = jellysim::testing;

namespace fs = std::filesystem;

namespace {

using Result = cli::CliResult;

Result run_cli(const std::string& args) { return cli::run_jellysim(args); }
std::string read_file(const fs::path& p) { return cli::read_text_file(p); }
fs::path fresh_dir(const std::string& name) { return cli::fresh_scratch_dir("cli_" + name); }

nlohmann::json summary_of(const fs::path& dir) { return nlohmann::json::parse(read_file(dir / "summary.json")); }

}  // namespace

TEST(Cli, HelpDocumentsCommands) {
  const Result r = run_cli("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* word : {"run", "experiment", "scenes"}) EXPECT_NE(r.output.find(word), std::string::npos) << word;
  const Result sub = run_cli("run --help");
  EXPECT_EQ(sub.exit_code, 0);
  for (const char* word : {"--out", "--set", "--duration"}) EXPECT_NE(sub.output.find(word), std::string::npos);
}

// Every --set example a command's help shows runs (they once named fields only swinging-bar has).
TEST(Cli, EverySetExampleInTheHelpRuns) {
  const std::regex example(R"(--set ([a-z_.]+=[^\s)`]+))");
  const std::pair<std::string, std::string> commands[] = {
      {"run", std::string("run --duration 0.1") + jellysim::testing::kPreviewGrid},
      {"simulate", std::string("simulate --duration 0.1") + jellysim::testing::kPreviewGrid},
      {"sweep", "sweep --duration 0.1 --set tank.cells=[96,256]"},
      {"experiment", "experiment swinging-bar --duration 0.5"},
  };
  for (const auto& [command, run_args] : commands) {
    const Result help = run_cli(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command;
    std::string sets;
    int count = 0;
    for (auto it = std::sregex_iterator(help.output.begin(), help.output.end(), example); it != std::sregex_iterator();
         ++it) {
      const std::string set = (*it)[1].str();
      if (std::regex_match(set, std::regex(R"([a-z_.]+=(value|[A-Z]+))"))) continue;  // syntax, not an example
      sets += " --set " + set;
      ++count;
    }
    EXPECT_EQ(count, 2) << command << " --help shows two examples:\n" << help.output;
    const fs::path dir = fresh_dir("set_example_" + command);
    const Result r = run_cli(run_args + sets + " --quiet --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << run_args << sets << "\n" << r.output;
  }
}

// `jellysim scenes run` and `scenes simulate` print the scenes those commands run.
TEST(Cli, ScenesPrintsTheCommandsScenesUnderTheirNames) {
  const Result run = run_cli("scenes run");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, run_cli("scenes animation").output);
  const Result simulate = run_cli("scenes simulate");
  EXPECT_EQ(simulate.exit_code, 0) << simulate.output;
  EXPECT_EQ(simulate.output, run_cli("scenes jellyfish").output);
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
  // An empty --duration once ran the whole default; an option after --out became a directory.
  for (const char* args : {"simulate --duration '' --quiet --out /tmp/jellysim_cli_never", "simulate --out ''",
                           "simulate --out --quiet", "run --out -x"}) {
    const Result r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string(args).find("--duration") != std::string::npos ? "--duration" : "--out"),
              std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(fs::exists("/tmp/jellysim_cli_never"));
  EXPECT_FALSE(fs::exists("--quiet"));
  EXPECT_FALSE(fs::exists("-x"));
  const Result r = run_cli("experiment no-such-thing --out " + fresh_dir("unknown").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("swinging-bar"), std::string::npos) << r.output;  // lists known names
}

// Issue 23's reproducers: each was silently ignored, run, or reported as a divergence; each is
// now a usage error naming what is wrong, with nothing written.
TEST(Cli, ContradictoryOrSmuggledSettingsAreUsageErrors) {
  const fs::path dir = fresh_dir("hostile");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--set scene=driven-cavity", "scene kind"},
      {"--duration 0.05 --set duration=0.1", "give it once"},
      {"--set 'duration=0.1\ntank.cells=[8, 8]'", "line break"},
      {"--set a..b=1", "empty part"},
      {"--set coupling.min_dt=0.1 --set coupling.max_dt=0.01", "coupling.min_dt"},
      {"--duration 1e18", "frames"},
      {"--set output.frame_interval=1e-9", "output.frame_interval"},
      {"--set output.frame_interval=1e-7 --duration 0.01", "coupling.min_dt"},
      {"/dev/zero", "not a regular file"},  // read until memory ran out
      // Memory (issue 23): estimated from the settings before anything is allocated.
      {"--set jellyfish.spacing=1e-9", "of memory"},           // grew to 16.7 GB
      {"--set jellyfish.height=50", "cannot fit in the tank"},  // 280000 m: std::bad_alloc building the markers
      {"--memory-limit 100M --set 'tank.cells=[1024, 1024]'", "budget of 100 MiB"},
      {"--memory-limit 12Q", "not a size"},
  };
  for (const auto& [args, named] : cases) {
    const Result r = run_cli("simulate --quiet --out " + dir.string() + " " + args);  // '…' keeps the line break
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir)) << args;
  }
}

// A modulus of 1e200 Pa or a tank 1e308 m high ran into NaN and crashed (a NaN position indexed
// out of the fluid grid, tested in tests/fluid); such values are now outside the fields' ranges.
// Issue 36: one resolver (scene::resolve_config) for every command; `view` once alone let
// `--set scene=` through. Each refuses it with the same message and exit 2, before any window,
// run or batch (the refusal comes first, so `view` needs no display here).
TEST(Cli, EveryCommandRefusesSetSceneTheSameWay) {
  const fs::path dir = fresh_dir("set_scene");
  fs::create_directories(dir);
  std::ofstream(dir / "plan.toml") << "duration = 0.1\n[product]\n\"jellyfish.frequency\" = [0.5]\n";
  const std::string message = "--set scene: the scene kind cannot be changed by --set; give a scene file instead";
  for (const std::string& command :
       {std::string("view --frames 1"), std::string("simulate --quiet"), std::string("run --quiet"),
        std::string("sweep --quiet"), std::string("experiment swinging-bar --quiet"),
        "batch " + (dir / "plan.toml").string() + " --quiet"}) {
    const std::string out = command.starts_with("view") ? "" : " --out " + (dir / "out").string();
    const Result r = run_cli(command + " --set scene=driven-cavity" + out);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << command << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << command;
  }
  fs::remove_all(dir);
}

TEST(Cli, PhysicalParametersHaveUpperBounds) {
  const fs::path dir = fresh_dir("upper_bounds");
  for (const char* field : {"jellyfish.bell_modulus=1e200", "jellyfish.muscle_modulus=1e308", "tank.height=1e308",
                            "jellyfish.neural_delay=1e308",
                            // issue 35, item 7: NaN metrics reported "ok", and NaN states ended at a chart
                            "tank.density=1e308", "tank.density=1e-308"}) {
    const Result r = run_cli(std::string("simulate --quiet --set ") + field + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << field << "\n" << r.output;
    const std::string key = std::string(field).substr(0, std::string(field).find('='));
    EXPECT_NE(r.output.find("field '" + key + "'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("out of range"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir));
  }
}

// A polygon obstacle's file (issue 23): a regular file of at most a few MiB and 10,000 vertices,
// every non-blank line exactly two numbers; anything else is refused naming the file and line.
TEST(Cli, PolygonFilesAreReadStrictly) {
  const fs::path dir = fresh_dir("polygon_files");
  fs::create_directories(dir);
  const std::string scene_text = read_file(fs::path(JELLYSIM_SOURCE_DIR) / "scenes/obstacles.toml");
  const std::string rock = "file = \"scenes/rock.txt\"";
  ASSERT_NE(scene_text.find(rock), std::string::npos);
  auto run_with = [&](const fs::path& polygon) {
    std::string text = scene_text;
    text.replace(text.find(rock), rock.size(), "file = \"" + polygon.string() + "\"");
    std::ofstream(dir / "scene.toml") << text;
    return run_cli("simulate " + (dir / "scene.toml").string() + " --quiet --duration 0.05 --out " +
                   (dir / "out").string());
  };
  auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir / name) << content;
    return dir / name;
  };
  std::string many;
  for (int k = 0; k <= 10000; ++k) many += "0.1 0.1\n";
  const fs::path big = write("big.txt", "");
  fs::resize_file(big, (4u << 20) + 1);
  const std::vector<std::pair<fs::path, std::string>> cases{
      {"/dev/zero", "not a regular file"},
      {dir, "not a regular file"},
      {dir / "missing.txt", "cannot be read"},
      {write("letter.txt", "0.10 0.12\nO.6 0.6\n0.12 0.14\n"), "line 2"},
      {write("three.txt", "0.10 0.12 0.3\n"), "line 1"},
      {write("word.txt", "# rock\n0.10 0.12\nnan 0.1\n"), "line 3"},
      {big, "bytes"},
      {write("many.txt", many), "more than 10000 vertices"},
  };
  for (const auto& [polygon, named] : cases) {
    const Result r = run_with(polygon);
    EXPECT_EQ(r.exit_code, 2) << polygon << "\n" << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << polygon << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << polygon;
  }
  fs::remove_all(dir);
}

TEST(Cli, BadSetValueNamesFieldAndLeavesNoOutput) {
  const fs::path dir = fresh_dir("bad_set");
  Result r = run_cli("experiment swinging-bar --quiet --out " + dir.string() + " --set bar.point_mass=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.point_mass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("out of range"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
  r = run_cli("experiment swinging-bar --quiet --out " + dir.string() + " --set time.integrator=rk7");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("dopri5"), std::string::npos) << r.output;  // lists the allowed values
  r = run_cli("run --quiet --out " + dir.string() + " --duration -3");  // the default (jellyfish) scene
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("duration"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(Cli, BadSceneFileNamesFieldAndLeavesNoOutput) {
  const fs::path dir = fresh_dir("bad_scene");
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar]\nsegmnets = 4\n";
  Result r = run_cli("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.segmnets"), std::string::npos) << r.output;
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar]\nsegments = \"many\"\n";
  r = run_cli("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bar.segments"), std::string::npos) << r.output;
  std::ofstream(scene) << "scene = \"swinging-bar\"\n[bar\n";
  r = run_cli("run --quiet " + scene.string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("scene.toml:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(Cli, SwingingBarWritesItsOutputs) {
  const fs::path dir = fresh_dir("bar");
  const Result r = run_cli("experiment swinging-bar --quiet --duration 4 --out " + dir.string());
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
  const std::string args =
      "experiment swinging-bar --quiet --duration 3 --set time.adaptive=true --set time.integrator=rk4 --out ";
  ASSERT_EQ(run_cli(args + a.string()).exit_code, 0);
  ASSERT_EQ(run_cli(args + b.string()).exit_code, 0);
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
  const Result r = run_cli(
      "experiment swinging-bar --quiet --duration 50 --set time.integrator=forward-euler --set time.dt=0.2 --out " +
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
  const Result r = run_cli("experiment integrator-order --quiet --out " + dir.string());
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

// Ghia et al. tabulate Re = 100, 400, 1000 and 3200: the comparison is written for those only
// (a short run on a coarse grid: only which files and keys appear is checked).
TEST(Cli, DrivenCavityComparesWithGhiaAtEveryTabulatedReynoldsNumberOnly) {
  for (const auto& [re, tabulated] : {std::pair{"400", true}, {"3200", true}, {"500", false}}) {
    const fs::path dir = fresh_dir(std::string("cavity_re") + re);
    const Result r = run_cli(std::string("experiment driven-cavity --quiet --re ") + re +
                             " --grid 8 --set figure_8_7.enabled=false --set output.frame_interval=0"
                             " --set output.tracers_per_side=0 --set cavity.max_time=0.5 --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto summary = summary_of(dir);
    EXPECT_TRUE(summary.contains("psi_min")) << re;
    EXPECT_TRUE(summary.contains("vortex_centre_x")) << re;
    EXPECT_EQ(fs::exists(dir / "ghia_comparison.csv"), tabulated) << re;
    EXPECT_EQ(summary.contains("ghia_max_abs_u_error"), tabulated) << re;
    EXPECT_EQ(summary.contains("ghia_psi_min"), tabulated) << re;
    if (std::string(re) == "400") {
      EXPECT_EQ(summary["ghia_psi_min"].get<double>(), -0.113909);
      EXPECT_NE(read_file(dir / "ghia_comparison.csv").find("\nu,0.9766,0.75837,"), std::string::npos);
    }
    fs::remove_all(dir);
  }
}

TEST(Cli, DrivenCavityWritesProfilesAndGhiaComparison) {
  const fs::path dir = fresh_dir("cavity");
  const Result r = run_cli("experiment driven-cavity --quiet --solver eulerian --re 100 --grid 16 "
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
  // The primary vortex (the stream function's minimum) next to Ghia et al.'s Table V; at 16²
  // measured (0.610, 0.751), ψ_min = −0.0916: about half these tolerances.
  EXPECT_EQ(summary["ghia_vortex_centre_x"].get<double>(), 0.6172);
  EXPECT_EQ(summary["ghia_vortex_centre_y"].get<double>(), 0.7344);
  EXPECT_EQ(summary["ghia_psi_min"].get<double>(), -0.103423);
  EXPECT_NEAR(summary["vortex_centre_x"].get<double>(), 0.6172, 0.015);
  EXPECT_NEAR(summary["vortex_centre_y"].get<double>(), 0.7344, 0.035);
  EXPECT_NEAR(summary["psi_min"].get<double>(), -0.103423, 0.025);
  EXPECT_EQ(run_cli("experiment driven-cavity --quiet --solver rk4 --out " + dir.string() + "_bad").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir.string() + "_bad"));
  // With the default scheme (Koren) even the 16² flow settles below the default tolerance (1e-6);
  // a time limit before that stops the run, and the summary says which; with --steady-tolerance
  // 1e-2 it stops when the change rate falls below that, and convergence.csv's history ends there.
  EXPECT_TRUE(summary["steady"].get<bool>());
  EXPECT_EQ(summary["stopped_by"], "steady_tolerance");
  EXPECT_LT(summary["final_change_rate"].get<double>(), 1e-6);
  EXPECT_EQ(summary["steady_tolerance"].get<double>(), 1e-6);
  EXPECT_TRUE(fs::exists(dir / "convergence.png"));
  const fs::path limited = fresh_dir("cavity_limited");
  ASSERT_EQ(run_cli("experiment driven-cavity --quiet --grid 16 --set cavity.max_time=2 --set figure_8_7.enabled=false "
                    "--out " + limited.string()).exit_code, 0);
  const auto unsettled = summary_of(limited);
  EXPECT_FALSE(unsettled["steady"].get<bool>());
  EXPECT_EQ(unsettled["stopped_by"], "max_time");
  EXPECT_GE(unsettled["final_change_rate"].get<double>(), 1e-6);
  EXPECT_EQ(unsettled["simulated_seconds"].get<double>(), 2.0);
  const fs::path loose = fresh_dir("cavity_loose");
  ASSERT_EQ(run_cli("experiment driven-cavity --quiet --grid 16 --steady-tolerance 1e-2 --set figure_8_7.enabled=false "
                    "--out " + loose.string()).exit_code, 0);
  const auto stopped = summary_of(loose);
  EXPECT_TRUE(stopped["steady"].get<bool>());
  EXPECT_EQ(stopped["stopped_by"], "steady_tolerance");
  EXPECT_LT(stopped["final_change_rate"].get<double>(), 1e-2);
  EXPECT_LT(stopped["simulated_seconds"].get<double>(), 10.0);
  const std::string history = read_file(loose / "convergence.csv");
  EXPECT_EQ(history.substr(0, 14), "t,change_rate\n");
  const std::string last = history.substr(history.rfind('\n', history.size() - 2) + 1);
  EXPECT_DOUBLE_EQ(std::stod(last.substr(last.find(',') + 1)), stopped["final_change_rate"].get<double>());
  EXPECT_EQ(run_cli("experiment taylor-green --quiet --steady-tolerance 1e-3 --out " + loose.string() + "_bad").exit_code, 2);
  fs::remove_all(dir);
  fs::remove_all(limited);
  fs::remove_all(loose);
}

TEST(Cli, TaylorGreenMeasuresTheOrderOfEverySchemeOfBothSolvers) {
  const fs::path dir = fresh_dir("taylor_green");
  const Result r = run_cli("experiment taylor-green --quiet --set 'study.grids=[16, 32, 64]' --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto orders = summary_of(dir)["measured_orders_l2"];
  EXPECT_GT(orders["eulerian"]["donor-cell"].get<double>(), 1.7);  // second order in space
  EXPECT_GT(orders["eulerian"]["koren"].get<double>(), 2.2);
  EXPECT_NEAR(orders["semi-lagrangian"]["linear"].get<double>(), 0.9, 0.2);  // first order (splitting, Δt ∝ Δx)
  EXPECT_GT(orders["semi-lagrangian"]["maccormack"].get<double>(), 1.8);
  EXPECT_GT(orders["semi-lagrangian"]["bfecc"].get<double>(), 1.8);
  EXPECT_GT(orders["semi-lagrangian"]["cubic"].get<double>(), 1.8);
  const std::string csv = read_file(dir / "taylor_green.csv");
  EXPECT_EQ(csv.substr(0, 23), "solver,scheme,cells,dx,");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + (3 + 4) * 3);  // (3 + 4 schemes) x grids
  EXPECT_NE(csv.find("\nsemi-lagrangian,bfecc,64,"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "taylor_green.png"));
  const Result one_grid = run_cli("experiment taylor-green --quiet --set 'study.grids=[32]' --out " + dir.string() + "_one");
  EXPECT_EQ(one_grid.exit_code, 2);
  EXPECT_NE(one_grid.output.find("study.grids"), std::string::npos) << one_grid.output;
  EXPECT_FALSE(fs::exists(dir.string() + "_one"));
  fs::remove_all(dir);
}

TEST(Cli, SolverCostTablesEveryCombination) {
  const fs::path dir = fresh_dir("solver_cost");
  const Result r = run_cli("experiment solver-cost --quiet --set 'study.grids=[16, 32]' --set study.steps=2 --out " +
                            dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string csv = read_file(dir / "solver_cost.csv");
  EXPECT_EQ(csv.substr(0, 29), "solver,pressure_solver,cells,");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3 * 2);  // solvers x pressure solvers (sor, multigrid, fft) x grids
  EXPECT_NE(csv.find("semi-lagrangian,multigrid,32,"), std::string::npos);
  const Result bad = run_cli("experiment solver-cost --quiet --set 'study.pressure_solvers=[\"jacobi\"]' --out " +
                              dir.string() + "_bad");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("study.pressure_solvers"), std::string::npos) << bad.output;
  fs::remove_all(dir);
}

// Started as several MPI ranks (mpirun -n 3 jellysim sweep), every command but `batch` would write
// the same files three times at once: it is refused, pointing to `batch`.
TEST(Cli, CommandsOtherThanBatchRefuseSeveralMpiRanks) {
  const fs::path dir = fresh_dir("mpi_ranks");
  ::setenv("OMPI_COMM_WORLD_SIZE", "3", 1);
  const Result sweep = run_cli("sweep --duration 0.1 --quiet --out " + dir.string());
  const Result simulate = run_cli("simulate --duration 0.1 --quiet --out " + dir.string());
  ::setenv("OMPI_COMM_WORLD_SIZE", "1", 1);
  const Result alone = run_cli(std::string("simulate --duration 0.05 --set output.pictures=false --quiet") +
                               jellysim::testing::kPreviewGrid + " --out " + dir.string());
  ::unsetenv("OMPI_COMM_WORLD_SIZE");
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_NE(sweep.output.find("`jellysim sweep` was started as 3 MPI ranks"), std::string::npos) << sweep.output;
  EXPECT_NE(sweep.output.find("jellysim batch"), std::string::npos) << sweep.output;
  EXPECT_EQ(simulate.exit_code, 2) << simulate.output;
  EXPECT_EQ(alone.exit_code, 0) << alone.output;  // one rank is one process
  fs::remove_all(dir);
}
