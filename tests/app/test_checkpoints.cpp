// Checkpoints and --resume (issue 23): a run killed with SIGKILL after a checkpoint continues with
// `jellysim simulate --resume DIR` and ends with the files of the uninterrupted run, byte for
// byte; a checkpoint that cannot be continued is refused with exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using jellysim::testing::fresh_scratch_dir;
using jellysim::testing::kPreviewGrid;
using jellysim::testing::read_text_file;
using jellysim::testing::run_jellysim;
using jellysim::testing::spawn_jellysim;

//// Waits until `file` exists while the process runs; false when it ended first.
bool wait_for(const fs::path& file, pid_t pid) {
  for (;;) {
    if (fs::exists(file)) return true;
    if (::waitpid(pid, nullptr, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::vector<std::string> split(const std::string& args) {
  std::vector<std::string> words;
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

/// summary.json without its wall-clock figures (they differ from run to run by nature; the 3D
/// run's milliseconds a step and their split too).
std::string summary_without_timings(const fs::path& file) {
  std::istringstream in(read_text_file(file));
  std::string kept;
  const auto timed = [](const std::string& line) {
    for (const char* key : {"wall_seconds", "realtime_factor", "\"ms_per_step\"", "\"transfer\":", "\"fluid\":", "\"krylov\":"})
      if (line.find(key) != std::string::npos) return true;
    return false;
  };
  for (std::string line; std::getline(in, line);)
    if (!timed(line)) kept += line + "\n";
  return kept;
}

/// Every file of a results directory but summary.json, by relative path.
std::vector<fs::path> files_of(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "summary.json") files.push_back(e.path().lexically_relative(dir));
  std::sort(files.begin(), files.end());
  return files;
}

/// Runs `args` uninterrupted, and again with checkpoints, killed with SIGKILL at frame `kill_at`
/// (after the first checkpoint; `frame_file` names a frame's file) and resumed: both directories
/// must hold the same bytes.
void expect_resumed_run_is_uninterrupted_run(const std::string& name, const std::string& args, double every_s,
                                              int kill_at, const char* frame_file = "body_%06d.vtp") {
  const fs::path whole = fresh_scratch_dir(name + "_whole"), resumed = fresh_scratch_dir(name + "_resumed");
  const jellysim::testing::CliResult reference = run_jellysim("simulate " + args + " --quiet --out " + whole.string());
  ASSERT_EQ(reference.exit_code, 0) << reference.output;

  std::vector<std::string> killed{"simulate", "--quiet", "--out", resumed.string(), "--checkpoint-every",
                                  std::to_string(every_s)};
  for (const std::string& w : split(args)) killed.push_back(w);
  const pid_t pid = spawn_jellysim(killed);
  ASSERT_GT(pid, 0);
  const bool checkpointed = wait_for(resumed / "checkpoint.jellysim", pid);
  char frame[32];
  std::snprintf(frame, sizeof frame, frame_file, kill_at);
  const bool running = checkpointed && wait_for(resumed / "frames" / frame, pid);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(running) << "the run ended before it could be killed after a checkpoint";

  const jellysim::testing::CliResult again = run_jellysim("simulate --resume " + resumed.string() + " --quiet");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_FALSE(fs::exists(resumed / "checkpoint.jellysim")) << "a completed run keeps no checkpoint";

  const std::vector<fs::path> files = files_of(whole);
  ASSERT_EQ(files, files_of(resumed));
  for (const fs::path& f : files) EXPECT_EQ(read_text_file(whole / f), read_text_file(resumed / f)) << f;
  EXPECT_EQ(summary_without_timings(whole / "summary.json"), summary_without_timings(resumed / "summary.json"));
  fs::remove_all(whole);
  fs::remove_all(resumed);
}

// The built-in scene (on the preview grid) with the Eulerian solver on the half tank (the mirror
// symmetry), FFT pressure, the semi-implicit coupling; VTK files per frame, their .pvd collection
// continued.
TEST(Checkpoints, AKilledRunResumesToTheUninterruptedRunsBytes) {
  expect_resumed_run_is_uninterrupted_run(
      "builtin", std::string("--duration 0.6 --set output.pictures=false --set tank.solver=eulerian") + kPreviewGrid, 0.2, 9);
}

// Every history a step reads: the second-order semi-Lagrangian step's last velocities (the built-in
// fluid), multigrid pressure solves started from extrapolated and last pressures, the mobility
// matrix kept between steps, the whole tank without symmetry, tracers drawn in pictures.
TEST(Checkpoints, HistoriesOfTheSolversSurviveAResume) {
  expect_resumed_run_is_uninterrupted_run(
      "histories",
      std::string("--duration 0.5 --set tank.solver=semi-lagrangian --set tank.advection=maccormack "
                  "--set tank.pressure_solver=multigrid --set tank.symmetry=none --set coupling.mobility_rebuild=0.5 "
                  "--set tank.tracers_per_side=10 --set output.picture_every=5") + kPreviewGrid,
      0.15, 8);
}

// The 3D scene (issue 40) on the tiny tank, a whole cycle, 8 frames, the flow and the markers per
// frame (.vti, .vtp, .obj, the .pvd continued): the water, the coupling's last increment and
// markers, the frame clock and the frames recorded survive a SIGKILL (about 8 s: Release only).
TEST(Checkpoints, SlowTheThreeDimensionalRunResumesToItsBytes) {
  expect_resumed_run_is_uninterrupted_run(
      "threed",
      std::string(JELLYSIM_SOURCE_DIR) + "/scenes/jellyfish-3d.toml --set tank.size=[0.1,0.1,0.1] --set "
      "tank.cells=[16,16,16] --set jellyfish.position=[0,0.03] --set jellyfish.tentacle_length=0.005 --set "
      "output.frames_per_cycle=8 --duration 1.4285714286 --set output.vtk=true",
      0.3, 4, "bell_%06d.vtp");
}

TEST(Checkpoints, WhatCannotBeResumedIsAnInputError) {
  const fs::path dir = fresh_scratch_dir("resume_refused");
  // A finished run has no checkpoint.
  ASSERT_EQ(run_jellysim(std::string("simulate --duration 0.1 --set output.pictures=false --quiet --checkpoint-every 0.05") +
                         kPreviewGrid + " --out " + dir.string()).exit_code, 0);
  jellysim::testing::CliResult r = run_jellysim("simulate --resume " + dir.string() + " --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no checkpoint there"), std::string::npos) << r.output;
  // A damaged checkpoint (one byte changed) is refused by its checksum.
  const pid_t pid = spawn_jellysim({"simulate", "--duration", "2", "--set", "output.pictures=false", "--quiet",
                                    "--set", "tank.cells=[96,192]", "--checkpoint-every", "0.05", "--out", dir.string()});
  ASSERT_GT(pid, 0);
  const bool checkpointed = wait_for(dir / "checkpoint.jellysim", pid);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(checkpointed);
  const fs::path file = dir / "checkpoint.jellysim";
  std::string bytes = read_text_file(file);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  std::ofstream(file, std::ios::binary) << bytes;
  r = run_jellysim("simulate --resume " + dir.string() + " --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("checksum"), std::string::npos) << r.output;
  // The configuration comes from the checkpoint: no scene, --set or --duration beside --resume.
  r = run_jellysim("simulate --resume " + dir.string() + " --set jellyfish.frequency=0.9");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("excludes"), std::string::npos) << r.output;
  r = run_jellysim("simulate --checkpoint-every 0 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2);
  fs::remove_all(dir);
}

/// Starts `simulate ARGS --checkpoint-every 0.05 --out DIR` on the preview grid, long enough to be
/// killed, and kills it (SIGKILL) once its first checkpoint is there.
void killed_after_a_checkpoint(const fs::path& dir, const std::vector<std::string>& args) {
  std::vector<std::string> all{"simulate", "--duration", "5", "--set", "output.pictures=false", "--set",
                               "output.vtk=false", "--quiet", "--checkpoint-every", "0.05", "--out", dir.string()};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = spawn_jellysim(all);
  ASSERT_GT(pid, 0);
  const bool checkpointed = wait_for(dir / "checkpoint.jellysim", pid);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(checkpointed) << "the run ended before its first checkpoint";
}

void expect_refused(const jellysim::testing::CliResult& r, const std::vector<std::string>& words) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const std::string& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << w << " in: " << r.output;
}

// Issue 35 item 3: run E's checkpoint copied into run D's directory does not resume there (it
// once continued D's frames with E's); item 9: a checkpoint is checked against the size its
// configuration implies before its state is read (a sparse 3 GB file is refused at once).
TEST(Checkpoints, ACheckpointResumesOnlyItsOwnRunAndItsSizeIsChecked) {
  const fs::path d = fresh_scratch_dir("foreign_d"), e = fresh_scratch_dir("foreign_e");
  killed_after_a_checkpoint(d, {"--set", "tank.cells=[48,96]"});
  killed_after_a_checkpoint(e, {"--set", "tank.cells=[48,96]", "--set", "jellyfish.frequency=0.9"});
  const std::string own = read_text_file(d / "checkpoint.jellysim");
  fs::copy_file(e / "checkpoint.jellysim", d / "checkpoint.jellysim", fs::copy_options::overwrite_existing);
  const std::string metrics = fs::exists(d / "metrics.csv") ? read_text_file(d / "metrics.csv") : "";
  expect_refused(run_jellysim("simulate --resume " + d.string() + " --quiet"),
                 {(d / "checkpoint.jellysim").string(), (d / "manifest.txt").string(), "another run"});
  EXPECT_FALSE(fs::exists(d / "summary.json"));

  std::ofstream(d / "checkpoint.jellysim", std::ios::binary) << own;  // its own, grown to 3 GB (sparse)
  ASSERT_EQ(::truncate((d / "checkpoint.jellysim").c_str(), off_t{3} << 30), 0);
  expect_refused(run_jellysim("simulate --resume " + d.string() + " --quiet"),
                 {(d / "checkpoint.jellysim").string(), "bytes of state, more than this run's configuration"});
  ASSERT_EQ(::truncate((d / "checkpoint.jellysim").c_str(), 0), 0);  // garbage of 3 GB
  ASSERT_EQ(::truncate((d / "checkpoint.jellysim").c_str(), off_t{3} << 30), 0);
  expect_refused(run_jellysim("simulate --resume " + d.string() + " --quiet"),
                 {(d / "checkpoint.jellysim").string(), "not a whole jellysim checkpoint"});
  fs::remove_all(d);
  fs::remove_all(e);
}

// Issue 35 item 14: a resume whose IB2d .target file was deleted names that file (it once said the
// checkpoint's entries did not match).
TEST(Checkpoints, AResumeWhoseSceneFileIsGoneNamesIt) {
  const fs::path dir = fresh_scratch_dir("resume_target");
  fs::create_directories(dir);
  std::ofstream(dir / "s.vertex") << "3\n1.0 1.0\n1.2 1.0\n1.4 1.0\n";
  std::ofstream(dir / "s.spring") << "2\n1 2 10 0.2\n2 3 10 0.2\n";
  std::ofstream(dir / "s.target") << "1\n1 100\n";
  std::ofstream(dir / "scene.toml") << "scene = \"jellyfish\"\n[tank]\nwidth = 3.0\nheight = 3.0\ncells = [24, 24]\n"
                                       "[jellyfish]\nenabled = false\n[[objects]]\ntype = \"ib2d\"\nfiles = \""
                                    << (dir / "s").string() << "\"\n[[objects.schedules]]\nsprings = [1, 1]\n"
                                       "law = \"abs-cos\"\n";
  killed_after_a_checkpoint(dir / "out", {(dir / "scene.toml").string()});
  fs::remove(dir / "s.target");
  expect_refused(run_jellysim("simulate --resume " + (dir / "out").string() + " --quiet"),
                 {"'" + (dir / "s.target").string() + "', which is missing"});
  fs::remove_all(dir);
}

// Issue 35 item 4: two runs into one directory at once (`simulate` or `batch`): the second is
// refused, naming the directory and the first's pid; the lock a killed run left is not in the way.
TEST(Checkpoints, ADirectoryInUseIsRefusedToASecondRun) {
  const fs::path dir = fresh_scratch_dir("locked");
  const pid_t pid = spawn_jellysim({"simulate", "--duration", "5", "--set", "output.pictures=false", "--set",
                                    "output.vtk=false", "--quiet", "--set", "tank.cells=[48,96]", "--out", dir.string()});
  ASSERT_GT(pid, 0);
  const bool started = wait_for(dir / "manifest.txt", pid);
  const std::string holder = "in use by another jellysim run (pid " + std::to_string(pid) + ")";
  const std::string quick = std::string(" --duration 0.05 --set output.pictures=false --set output.vtk=false --quiet") +
                            " --set tank.cells=[48,96] --out " + dir.string();
  const jellysim::testing::CliResult second = run_jellysim("simulate" + quick);
  std::ofstream(dir.string() + ".toml") << "[product]\n\"jellyfish.frequency\" = [0.5]\n";
  const jellysim::testing::CliResult batch = run_jellysim("batch " + dir.string() + ".toml --quiet --out " + dir.string());
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(started);
  expect_refused(second, {"--out '" + dir.string() + "'", holder});
  expect_refused(batch, {"--out '" + dir.string() + "'", holder});
  ASSERT_TRUE(fs::exists(dir / ".jellysim.lock"));  // the killed run's: no one holds it
  const jellysim::testing::CliResult after = run_jellysim("simulate" + quick);
  EXPECT_EQ(after.exit_code, 0) << after.output;
  EXPECT_FALSE(fs::exists(dir / ".jellysim.lock"));  // released with the run
  fs::remove_all(dir);
  fs::remove(dir.string() + ".toml");
}

}  // namespace
