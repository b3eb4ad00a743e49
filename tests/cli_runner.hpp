#pragma once
// Shared by the end-to-end tests of the command line: run `jellysim ARGS`, read files back, and
// make a fresh scratch directory, start it in the background (signal and checkpoint tests). JELLYSIM_CLI_PATH is defined by tests/CMakeLists.txt.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <gtest/gtest.h>

extern char** environ;

namespace jellysim::testing {

/// `--set` of the built-in jellyfish scene on a grid four times coarser (96 × 192 cells, 16 across
/// the bell): tests of the commands' machinery run it at a sixtieth of the built-in grid's cost,
/// which the sanitizer pass needs. The built-in grid's swimming is tested in tests/jellyfish.
inline constexpr const char* kPreviewGrid = " --set tank.cells=[96,192]";


struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a shell command line; its output is what it writes to stdout.
inline CliResult run_command(const std::string& cmd) {
  CliResult r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe) != nullptr) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Runs the jellysim program with the given arguments (a shell command line).
inline CliResult run_jellysim(const std::string& args) {
  return run_command(std::string(JELLYSIM_CLI_PATH) + " " + args + " 2>&1");
}

inline std::string read_text_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A directory under the system temporary directory, removed first if it exists.
inline std::filesystem::path fresh_scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("jellysim_test_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

/// `jellysim ARGS --quiet --out DIR` is refused: exit 2, a message naming `named`, DIR not created.
inline void expect_refused(const std::string& args, const std::string& named, const std::filesystem::path& dir) {
  const CliResult r = run_jellysim(args + " --quiet --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
  EXPECT_NE(r.output.find(named), std::string::npos) << args << ": " << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir)) << args;
}

/// Starts jellysim with `args` (no shell, output discarded) and returns its pid, or -1.
inline pid_t spawn_jellysim(const std::vector<std::string>& args) {
  std::vector<std::string> all{JELLYSIM_CLI_PATH};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

}  // namespace jellysim::testing
