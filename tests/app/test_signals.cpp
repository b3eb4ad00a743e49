// SIGINT / SIGTERM / SIGHUP during a run (issues 23, 35): the run stops at the next step boundary,
// keeps what it computed, says so in summary.json and exits with 128 + the signal, leaving no
// temporary file; a terminal's Ctrl-C (the whole process group) and a closed standard output too.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../cli_runner.hpp"
#include "jellysim/render/video.hpp"

namespace {

namespace fs = std::filesystem;
using jellysim::testing::spawn_jellysim;

// Waits (up to a minute) until `file` exists: the run is then inside its step loop.
bool wait_for(const fs::path& file) {
  for (int k = 0; k < 6000; ++k) {
    if (fs::exists(file)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

std::string name_of(int signal_number) {
  return signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "SIGHUP";
}

void expect_interrupted_run(int signal_number, int expected_exit) {
  const fs::path dir = jellysim::testing::fresh_scratch_dir("signal_" + std::to_string(signal_number));
  const pid_t pid = spawn_jellysim({"simulate", "--quiet", "--set", "tank.cells=[96,192]", "--out", dir.string()});
  ASSERT_GT(pid, 0);
  if (!wait_for(dir / "frames" / "body_000002.vtp")) {  // the third frame: inside the step loop
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    FAIL() << "the run never reached its third frame";
  }
  ::kill(pid, signal_number);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), expected_exit);
  const std::string summary = jellysim::testing::read_text_file(dir / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("interrupted by " + name_of(signal_number)), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "metrics.csv"));
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(Signals, SigintStopsTheRunKeepsItsResultsAndExits130) { expect_interrupted_run(SIGINT, 130); }
TEST(Signals, SigtermStopsTheRunKeepsItsResultsAndExits143) { expect_interrupted_run(SIGTERM, 143); }
// A closed terminal or SSH session (issue 35, item 1: it killed the run, exit 129, no summary).
TEST(Signals, SighupStopsTheRunKeepsItsResultsAndExits129) { expect_interrupted_run(SIGHUP, 129); }

/// Starts jellysim in a process group of its own, as a shell starts a job in a terminal, with
/// `stdout_fd` as its standard output (-1: /dev/null) and `path_first` in front of PATH.
pid_t spawn_job(const std::vector<std::string>& args, const std::string& path_first = "", int stdout_fd = -1) {
  std::vector<std::string> all{JELLYSIM_CLI_PATH};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::string(*e).rfind("PATH=", 0) != 0) env_text.emplace_back(*e);
  const char* path = std::getenv("PATH");
  env_text.push_back("PATH=" + (path_first.empty() ? "" : path_first + ":") + (path ? path : "/usr/bin:/bin"));
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdout_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stdout_fd, STDOUT_FILENO);
  else posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t defaults;  // a job started by a test runner may inherit SIGINT ignored
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&defaults, s);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), envp.data());
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

int wait_exit_code(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

/// Starts `jellysim run ARGS` as a terminal job, with an ffmpeg in front of the real one that, once
/// started, waits until Ctrl-C has been sent to the job's whole process group; returns how the
/// job exited. The frames (320 x 240: the caller sets the size) are larger than a pipe holds, so
/// they cannot all be sent before: the run is always interrupted while rendering.
int ctrl_c_while_encoding(const fs::path& dir, const std::vector<std::string>& args) {
  const std::string real_ffmpeg = jellysim::render::find_ffmpeg();
  fs::create_directories(dir / "bin");
  const fs::path started = dir / "ffmpeg_started", go = dir / "go";
  fs::remove(started);
  fs::remove(go);
  std::ofstream(dir / "bin" / "ffmpeg") << "#!/bin/sh\n: > '" << started.string() << "'\nwhile [ ! -e '" << go.string()
                                         << "' ]; do sleep 0.01; done\nexec '" << real_ffmpeg << "' \"$@\"\n";
  fs::permissions(dir / "bin" / "ffmpeg", fs::perms::owner_all);
  std::vector<std::string> all{"run"};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = spawn_job(all, (dir / "bin").string());
  if (pid <= 0) return -1;
  const bool encoding = wait_for(started);
  ::kill(-pid, SIGINT);  // the terminal's Ctrl-C: the whole group
  std::ofstream(go) << "";
  const int exit_code = wait_exit_code(pid);
  return encoding ? exit_code : -2;
}

const std::vector<std::string> kVideoRun{"--quiet", "--duration", "0.2", "--set", "tank.cells=[96,192]", "--set",
                                         "render.width=320", "--set", "render.height=240", "--set",
                                         "render.png_frames=false"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// Ctrl-C in a terminal signals the job's whole process group. While the video was being encoded
// that reached ffmpeg too, which died, and the run failed (exit 1, no summary, no video, no .glb).
// Now ffmpeg has a group of its own; jellysim stops rendering and finishes the video with the
// frames so far (issue 35, item 1).
TEST(Signals, CtrlCWhileEncodingTheVideoKeepsTheVideoAndTheSummary) {
  if (jellysim::render::find_ffmpeg().empty()) GTEST_SKIP() << "no ffmpeg";
  const fs::path dir = jellysim::testing::fresh_scratch_dir("ctrl_c_video");
  EXPECT_EQ(ctrl_c_while_encoding(dir, with(kVideoRun, {"--out", (dir / "out").string()})), 130);
  const std::string summary = jellysim::testing::read_text_file(dir / "out" / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("interrupted by SIGINT while rendering"), std::string::npos) << summary;
  for (const char* f : {"jellyfish.mp4", "jellyfish.glb", "metrics.csv"}) EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  EXPECT_GT(fs::file_size(dir / "out" / "jellyfish.mp4"), 0u);
  for (const auto& e : fs::recursive_directory_iterator(dir / "out"))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

// `jellysim run --checkpoint-every`: the checkpoint of the simulation's end stays until the
// animation is written, so a run stopped while rendering resumes (--resume renders again) to
// the outputs of the uninterrupted run, byte for byte (issue 35, item 15).
TEST(Signals, ARunStoppedWhileRenderingResumesToTheUninterruptedOutputs) {
  if (jellysim::render::find_ffmpeg().empty()) GTEST_SKIP() << "no ffmpeg";
  const fs::path dir = jellysim::testing::fresh_scratch_dir("run_resume");
  const fs::path out = dir / "out", reference = dir / "reference";
  ASSERT_EQ(ctrl_c_while_encoding(dir, with(kVideoRun, {"--checkpoint-every", "0.1", "--out", out.string()})), 130);
  ASSERT_TRUE(fs::exists(out / "checkpoint.jellysim"));
  const auto resumed = jellysim::testing::run_jellysim("run --quiet --resume " + out.string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  std::string args;
  for (const std::string& a : kVideoRun) args += " '" + a + "'";
  const auto whole = jellysim::testing::run_jellysim("run" + args + " --out " + reference.string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  EXPECT_FALSE(fs::exists(out / "checkpoint.jellysim"));
  EXPECT_NE(jellysim::testing::read_text_file(out / "summary.json").find("\"status\": \"ok\""), std::string::npos);
  for (const char* f : {"jellyfish.mp4", "jellyfish.glb", "metrics.csv", "slices.csv", "manifest.txt"})
    EXPECT_EQ(jellysim::testing::read_text_file(out / f), jellysim::testing::read_text_file(reference / f)) << f;
  fs::remove_all(dir);
}

// `jellysim batch ... | head -1`: a standard output nobody reads any more failed the next line
// with SIGPIPE, which killed the batch mid-way (exit 141, no batch.csv). Now printing stops and
// the batch finishes its work (issue 35, item 1). The pipe here is closed before the batch starts.
TEST(Signals, AClosedStandardOutputDoesNotStopTheBatch) {
  const fs::path dir = jellysim::testing::fresh_scratch_dir("closed_stdout");
  fs::create_directories(dir);
  std::ofstream(dir / "plan.toml") << "duration = 0.05\n[set]\n\"tank.cells\" = [48, 64]\n\"output.pictures\" = false\n"
                                      "\"output.vtk\" = false\n[product]\n\"jellyfish.frequency\" = [0.5, 0.9]\n";
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  ::close(ends[0]);  // the reader has gone
  const pid_t pid = spawn_job({"batch", (dir / "plan.toml").string(), "--threads", "1", "--out", (dir / "out").string()},
                              "", ends[1]);
  ::close(ends[1]);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit_code(pid), 0);
  EXPECT_TRUE(fs::exists(dir / "out" / "batch.csv"));
  EXPECT_TRUE(fs::exists(dir / "out" / "summary.json"));
  fs::remove_all(dir);
}

}  // namespace
