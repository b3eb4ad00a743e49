// `jellysim simulate` on a 3D scene (tank.geometry = "3d"; docs/three-d.md "The 3D scene"):
// scenes/jellyfish-3d.toml on a tiny tank (2.5 bell diameters a side, 16 cells: 6.4 across the
// bell, the quarter tank solved), the files it writes, the same bytes on one and two threads, and
// the bad values refused before anything is written.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "../cli_runner.hpp"

namespace cli = jellysim::testing;
namespace fs = std::filesystem;

namespace {

const std::string kScene3d = std::string(JELLYSIM_SOURCE_DIR) + "/scenes/jellyfish-3d.toml";
/// The tiny tank: 10 cm a side, 16 cells (6.25 mm), the aperture 3 cm up, 5 mm tentacles.
const std::string kTinyTank = kScene3d +
                              " --set tank.size=[0.1,0.1,0.1] --set tank.cells=[16,16,16] --set jellyfish.position=[0,0.03]"
                              " --set jellyfish.tentacle_length=0.005";
/// ... 8 frames a cycle and one frame (0.18 s, the first half of the contraction).
const std::string kTiny = kTinyTank + " --set output.frames_per_cycle=8 --duration 0.18";

fs::path fresh(const std::string& name) { return cli::fresh_scratch_dir("jelly3d_" + name); }

std::vector<std::vector<double>> read_rows(const std::string& csv, std::string& header) {
  std::istringstream text(csv);
  std::getline(text, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(text, line);) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

/// `jellysim ARGS` is refused: exit 2, the message naming `named`, no output directory.
void expect_refused(const std::string& args, const std::string& named) {
  cli::expect_refused(args, named, fresh("refused"));
}

}  // namespace

TEST(Jellyfish3dCli, SimulateWritesMetricsSummaryAndTheFlowOfEachFrame) {
  const fs::path dir = fresh("simulate");
  const cli::CliResult r =
      cli::run_jellysim("simulate " + kTiny + " --set output.vtk=true --set coupling.threads=1 --quiet --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"metrics.csv", "summary.json", "jellyfish.pvd", "frames/field_000000.vti", "frames/field_000001.vti",
                        "frames/bell_000000.obj", "frames/bell_000001.vtp"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // ParaView's series: the flow and every marker (the surface's triangles, the tentacles' lines,
  // each marker's velocity and force), two parts a frame.
  const std::string pvd = cli::read_text_file(dir / "jellyfish.pvd");
  EXPECT_NE(pvd.find("part=\"1\" name=\"bell\" file=\"frames/bell_000001.vtp\""), std::string::npos) << pvd;
  const std::string vtp = cli::read_text_file(dir / "frames" / "bell_000001.vtp");
  EXPECT_NE(vtp.find("NumberOfPoints=\"433\" NumberOfVerts=\"0\" NumberOfLines=\"12\" NumberOfStrips=\"0\" "
                     "NumberOfPolys=\"774\""),
            std::string::npos);
  for (const char* array : {"Name=\"velocity\" NumberOfComponents=\"3\"", "Name=\"force\" NumberOfComponents=\"3\""})
    EXPECT_NE(vtp.find(array), std::string::npos) << array;
  // The bell's surface: a vertex and a normal per shell vertex (measured, half-cell edges: 409 of
  // the 433 markers, the other 24 the twelve tentacles' nodes; 774 triangles).
  std::istringstream obj(cli::read_text_file(dir / "frames" / "bell_000001.obj"));
  int v = 0, vn = 0, f = 0;
  for (std::string line; std::getline(obj, line);) {
    v += line.starts_with("v ");
    vn += line.starts_with("vn ");
    f += line.starts_with("f ");
  }
  EXPECT_EQ(v, 409);
  EXPECT_EQ(vn, v);
  EXPECT_GT(f, v);
  std::string header;
  const auto rows = read_rows(cli::read_text_file(dir / "metrics.csv"), header);
  EXPECT_EQ(header, "t,x,y,z,velocity_x,velocity_y,velocity_z,speed,heading_deg,tilt_deg,axis_x,axis_y,axis_z,volume,"
                    "krylov_iterations");
  ASSERT_EQ(rows.size(), 2u);  // t = 0 and one frame at 1 / (0.7 · 8) s
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 15u);
    for (double v : row) EXPECT_TRUE(std::isfinite(v));
  }
  EXPECT_NEAR(rows[1][0], 1.0 / 5.6, 1e-12);
  // The symmetric stroke pushes the bell up its axis (measured, the shell at half-cell edges: the
  // centroid rises 2.354 mm, at 23.28 mm/s, the cavity shrinks from 23.28 to 19.02 ml, 0.8168 of
  // it); it stays on the axis and upright.
  EXPECT_NEAR(rows[1][2] - rows[0][2], 2.354e-3, 0.05e-3);
  EXPECT_NEAR(rows[1][5], 23.28e-3, 0.5e-3);
  EXPECT_NEAR(rows[1][13] / rows[0][13], 0.8168, 0.005);
  EXPECT_NEAR(rows[1][1], 0.0, 1e-12);
  EXPECT_NEAR(rows[1][3], 0.0, 1e-12);
  EXPECT_NEAR(rows[1][9], 0.0, 1e-6);

  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "ok");
  for (const char* key : {"distance_per_cycle_m", "first_cycle_m", "cycle_displacements_m", "heading_change_deg_per_cycle",
                          "cycle_heading_changes_deg", "final_heading_deg", "final_tilt_deg", "sideways_m", "grid",
                          "markers", "steps", "ms_per_step", "ms_per_step_split", "krylov_iterations_per_step",
                          "estimated_memory_bytes", "config"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["grid"]["symmetry"], "quarter");
  EXPECT_EQ(s["grid"]["solved_cells"], nlohmann::json::array({8, 16, 8}));
  EXPECT_NEAR(s["grid"]["cells_across_bell"].get<double>(), 6.4, 1e-12);
  EXPECT_GT(s["estimated_memory_bytes"].get<double>(), 0.0);
  fs::remove_all(dir);
}

// The water's rows and the transfer's slabs on a pool: one and two threads, the same bytes. Slow:
// 0.9 s in Release at a load average of 2.7, 15 s while two compilers ran on the 2-core machine
// (the two threads' barriers wait for a busy core), so the sanitizer pass leaves it out.
TEST(Determinism, Simulate3dIsTheSameForOneAndTwoThreadsSlow) {
  std::string csv[2];
  for (int threads : {1, 2}) {
    const fs::path dir = fresh("threads" + std::to_string(threads));
    const cli::CliResult r =
        cli::run_jellysim("simulate " + kTinyTank + " --set output.frames_per_cycle=16 --duration 0.09 --set "
                          "coupling.threads=" + std::to_string(threads) + " --set output.vtk=false --quiet --out " +
                          dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    csv[threads - 1] = cli::read_text_file(dir / "metrics.csv");
    fs::remove_all(dir);
  }
  EXPECT_FALSE(csv[0].empty());
  EXPECT_EQ(csv[0], csv[1]);
}

// A step that fails (here GMRES held to one iteration) ends the run: the frames so far are written,
// summary.json says when and where, exit 1.
TEST(Jellyfish3dCli, AFailedStepKeepsWhatWasRecordedAndSaysWhenAndWhere) {
  const fs::path dir = fresh("failed");
  const cli::CliResult r = cli::run_jellysim("simulate " + kTiny + " --set coupling.krylov_max_iterations=1 "
                                             "--set coupling.threads=1 --quiet --out " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "failed");
  const std::string failure = s["failure"];
  EXPECT_EQ(failure.rfind("simulation diverged at t = ", 0), 0u) << failure;
  EXPECT_NE(failure.find("(step 1): 3D swimmer: the semi-implicit solve did not converge"), std::string::npos) << failure;
  std::string header;
  EXPECT_EQ(read_rows(cli::read_text_file(dir / "metrics.csv"), header).size(), 1u);  // the frame at t = 0
  fs::remove_all(dir);
}

// SIGINT stops the run at the next frame boundary: the frames so far written, summary.json
// "interrupted" with the time and step, exit 130.
TEST(Jellyfish3dCli, SigintKeepsTheFramesSoFarAndExits130) {
  const fs::path dir = fresh("sigint");
  const pid_t pid = cli::spawn_jellysim({"simulate", kScene3d, "--set", "tank.size=[0.1,0.1,0.1]", "--set",
                                         "tank.cells=[16,16,16]", "--set", "jellyfish.position=[0,0.03]", "--set",
                                         "jellyfish.tentacle_length=0.005", "--set", "output.frames_per_cycle=16",
                                         "--set", "output.vtk=true", "--set", "coupling.threads=1", "--duration", "10",
                                         "--quiet", "--out", dir.string()});
  ASSERT_GT(pid, 0);
  for (int k = 0; k < 6000 && !fs::exists(dir / "frames" / "field_000001.vti"); ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "interrupted");
  EXPECT_EQ(s["failure"].get<std::string>().rfind("interrupted by SIGINT at t = ", 0), 0u) << s["failure"];
  std::string header;
  const std::size_t rows = read_rows(cli::read_text_file(dir / "metrics.csv"), header).size();
  EXPECT_GE(rows, 2u);
  EXPECT_EQ(s["frames"].get<std::size_t>(), rows);
  fs::remove_all(dir);
}

TEST(Jellyfish3dCli, BadValuesNameTheFieldAndWriteNothing) {
  expect_refused("simulate --set tank.cells=[96,192,96]", "tank.cells");          // three cells in 2D
  expect_refused("simulate --set jellyfish.pacemaker=true", "jellyfish.pacemaker");  // a 3D field in 2D
  expect_refused("simulate --set jellyfish.conduction_speed=0.25", "jellyfish.conduction_speed");
  expect_refused("simulate " + kTiny + " --set jellyfish.conduction_speed=-1", "jellyfish.conduction_speed");
  expect_refused("simulate " + kTiny + " --set tank.cells=[16,16]", "tank.cells");  // two cells in 3D
  expect_refused("simulate " + kTiny + " --set tank.cells=[15,16,16]", "even");     // odd across x = 0
  expect_refused("simulate " + kTiny + " --set tank.size=[0.1,-0.1,0.1]", "tank.size");
  expect_refused("simulate " + kTiny + " --set tank.size=[0.1,200,0.1]", "tank.size");
  expect_refused("simulate " + kTiny + " --set jellyfish.position=[0.01,0.03]", "jellyfish.position");
  expect_refused("simulate " + kTiny + " --set jellyfish.position=[0,0.09]", "jellyfish.position");  // lid
  expect_refused("simulate " + kTiny + " --set jellyfish.steering=true", "jellyfish.steering");
  expect_refused("simulate " + kTiny + " --set tank.convection=donor-cell", "tank.convection");
  expect_refused("simulate " + kTiny + " --set jellyfish.pacemaker=true --set jellyfish.pacemaker_azimuth_deg=90 "
                 "--set tank.symmetry=mirror", "tank.symmetry");
  expect_refused("run " + kTiny + " --set render.loop=true", "render.loop");  // the loop is the slice's
  expect_refused("experiment 3d-vs-axisymmetric --set jellyfish.pacemaker=true", "jellyfish.pacemaker");
}

// `jellysim run` on a 3D scene renders the simulated surface itself (no 2D→3D extrapolation): the
// frames, the .glb with a morph target per frame, the point cache, beside the simulation's files.
TEST(Jellyfish3dCli, RunRendersTheSimulatedSurface) {
  const fs::path dir = fresh("run");
  const cli::CliResult r = cli::run_jellysim("run " + kTiny + " --set render.width=160 --set render.height=120 "
                                             "--set render.video=false --set coupling.threads=1 --quiet --out " +
                                             dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"metrics.csv", "summary.json", "frames/frame_0000.png", "frames/frame_0001.png", "jellyfish.glb",
                        "viewer.html", "caches/jellyfish_1.pc2"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["command"], "run");
  EXPECT_EQ(s["animation"]["frames"], 2);
  EXPECT_GT(s["animation"]["vertices_per_frame"].get<double>(), 0.0);
  fs::remove_all(dir);
}

// `experiment 3d-vs-axisymmetric` (issue 40 part 4's check): the tiny tank for one cycle, 4 frames a
// cycle: both runs' displacements in comparison.csv, the axisymmetric run on the tank's x–y
// section with the same cells, the ratio in summary.json (2.6 s: Release pass only).
TEST(Jellyfish3dCli, SlowComparesWithTheAxisymmetricSolverAtEqualResolution) {
  const fs::path dir = fresh("compare");
  const cli::CliResult r = cli::run_jellysim("experiment 3d-vs-axisymmetric --set tank.size=[0.1,0.1,0.1] --set "
                                             "tank.cells=[16,16,16] --set jellyfish.position=[0,0.03] --set "
                                             "jellyfish.tentacle_length=0.005 --set output.frames_per_cycle=4 "
                                             "--duration 1.4285714285714286 --quiet --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::istringstream csv(cli::read_text_file(dir / "comparison.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "geometry,cycle,displacement_m");
  EXPECT_EQ(lines[1].rfind("3d,1,", 0), 0u);
  EXPECT_EQ(lines[2].rfind("axisymmetric,1,", 0), 0u);
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["cells_axisymmetric"], nlohmann::json::array({16, 16}));
  EXPECT_NEAR(s["cells_across_bell"].get<double>(), 6.4, 1e-12);
  EXPECT_TRUE(s["distance_per_cycle_ratio"].is_null());  // one cycle: no distance per cycle yet
  const double first3d = s["3d"]["first_cycle_m"], first_axi = s["axisymmetric"]["first_cycle_m"];
  EXPECT_NEAR(s["first_cycle_ratio"].get<double>(), first3d / first_axi, 1e-12);
  std::printf("  first cycle: 3D %.3f mm, axisymmetric %.3f mm\n", 1e3 * first3d, 1e3 * first_axi);
  EXPECT_NEAR(first3d, 29.42e-3, 0.2e-3);  // measured 29.419 mm (the shell at half-cell edges)
  EXPECT_NEAR(first_axi, 20.29e-3, 0.2e-3);  // measured 20.286 mm
  fs::remove_all(dir);
}

// `experiment convergence` on the 3D scene: NXxNYxNZ grids, the shell's edges following each grid.
// A smoke test of the command on two very coarse grids of the tiny tank without tentacles (3.2 and
// 4.8 cells across the bell, two cycles, 2.5 s: Release pass only); the study itself is
// docs/three-d.md's "The bell's grid convergence".
TEST(Jellyfish3dCli, SlowConvergenceStudyRunsTheShellOnEachGrid) {
  const fs::path dir = fresh("convergence");
  const cli::CliResult r = cli::run_jellysim("experiment convergence " + kScene3d +
                                             " --grids 8x8x8,12x12x12 --cycles 2 --set frames_per_cycle=4"
                                             " --set tank.size=[0.1,0.1,0.1] --set jellyfish.position=[0,0.03]"
                                             " --set jellyfish.tentacle_count=0 --quiet --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string header;
  const auto rows = read_rows(cli::read_text_file(dir / "convergence.csv"), header);
  EXPECT_EQ(header, "cells_x,cells_y,cells_across_bell,markers,first_cycle_m,distance_per_cycle_m,min_volume_ratio,"
                    "peak_speed_m_per_s,steps,wall_seconds,cells_z");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_NEAR(rows[0][2], 3.2, 1e-12);
  EXPECT_NEAR(rows[1][2], 4.8, 1e-12);
  EXPECT_EQ(rows[1][10], 12.0);
  EXPECT_GT(rows[1][3], rows[0][3]);  // more markers on the finer grid: the edges follow it
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["swimmer"], "3d shell bell");
  EXPECT_EQ(s["grids"][1]["cells"], nlohmann::json::array({12, 12, 12}));
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& cycles = s["grids"][k]["cycle_displacements_m"];
    ASSERT_EQ(cycles.size(), 2u);
    EXPECT_DOUBLE_EQ(cycles[0].get<double>(), rows[k][4]);  // first_cycle_m
    EXPECT_DOUBLE_EQ(cycles[1].get<double>(), rows[k][5]);  // the mean of cycles 2 … 2
  }
  EXPECT_NEAR(s["relative_change_finest"].get<double>(), std::abs(rows[1][5] - rows[0][5]) / std::abs(rows[1][5]), 1e-12);
  fs::remove_all(dir);
}

TEST(Jellyfish3dCli, ConvergenceStudyRefusesGridsOfTheWrongShapeAndFixedEdges) {
  const fs::path dir = fresh("convergence_bad");
  const std::string study = "experiment convergence " + kScene3d;
  cli::expect_refused(study + " --grids 16x24,32x48", "'16x24' is not NXxNYxNZ", dir);
  cli::expect_refused(study + " --grids 16x24x16,32x48x12", "coarsest first", dir);
  cli::expect_refused(study + " --grids 16x24x16,32x48x32 --set jellyfish.shell_edge=0.002", "field 'jellyfish.shell_edge'",
                      dir);
}
