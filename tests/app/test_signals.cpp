// SIGINT / SIGTERM during a run (issue 23): the run stops at the next step boundary, keeps what it
// computed, says so in summary.json and exits with 128 + the signal, leaving no temporary file.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>

#include "../cli_runner.hpp"

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
  EXPECT_NE(summary.find("interrupted by " + std::string(signal_number == SIGINT ? "SIGINT" : "SIGTERM")),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "metrics.csv"));
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(Signals, SigintStopsTheRunKeepsItsResultsAndExits130) { expect_interrupted_run(SIGINT, 130); }
TEST(Signals, SigtermStopsTheRunKeepsItsResultsAndExits143) { expect_interrupted_run(SIGTERM, 143); }

}  // namespace
