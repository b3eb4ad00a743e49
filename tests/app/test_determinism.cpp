// Determinism as a hash (issue 23, Box2D's practice): the main job's metrics.csv and the SPH
// larva's frames.csv are byte-identical for one and two threads, and, in an optimised build, equal
// to the fingerprints recorded in docs/output-hashes.txt (scripts/output-hashes.sh runs the same
// commands). A change that alters them on purpose re-records that file; one that alters them by
// accident fails here.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "../cli_runner.hpp"

namespace jellysim {
namespace {

namespace fs = std::filesystem;
using testing::fresh_scratch_dir;
using testing::read_text_file;
using testing::run_jellysim;

/// sha256 of a file, as sha256sum prints it.
std::string sha256(const fs::path& file) {
  const std::string cmd = "sha256sum '" + file.string() + "'";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) return "";
  char buf[128] = {};
  const std::string line = std::fgets(buf, sizeof buf, pipe) ? buf : "";
  ::pclose(pipe);
  return line.substr(0, line.find(' '));
}

/// The fingerprint docs/output-hashes.txt records for `name` (e.g. "run/metrics.csv").
std::string recorded(const std::string& name) {
  const std::string text = read_text_file(fs::path(JELLYSIM_SOURCE_DIR) / "docs" / "output-hashes.txt");
  const std::size_t at = text.find("  " + name + "\n");
  if (at == std::string::npos || at < 64) return "";
  return text.substr(at - 64, 64);
}

/// Runs `args` (with --out DIR --quiet) and returns the hash of DIR/file.
std::string hash_of(const std::string& args, const std::string& file, const std::string& dir_name) {
  const fs::path dir = fresh_scratch_dir(dir_name);
  const testing::CliResult r = run_jellysim(args + " --quiet --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string h = sha256(dir / file);
  fs::remove_all(dir);
  return h;
}

#ifdef NDEBUG
constexpr bool kOptimisedBuild = true;
#else
constexpr bool kOptimisedBuild = false;  // the sanitizer build (-O1) may round differently: threads only
#endif

// The main job exactly as scripts/output-hashes.sh runs it (3D outputs off; the rendering does not
// write metrics.csv; the preview grid, 96 × 192, so that the sanitizer pass can afford it), its
// marker-space table built on two threads (`coupling.threads`; the hash was recorded with one).
TEST(Determinism, MainJobMetricsHaveTheRecordedHash) {
  const std::string h = hash_of(
      std::string("run --set render.png_frames=false --set render.video=false --set render.glb=false "
                  "--set render.viewer=false --set coupling.threads=2") + testing::kPreviewGrid,
      "metrics.csv", "determinism_run");
  ASSERT_EQ(h.size(), 64u);
  if (kOptimisedBuild) {
    EXPECT_EQ(h, recorded("run/metrics.csv"));
  }
}

// IB2d's Hoover–Miller bell (4-point kernel, periodic seams, target points) at N = 32: the
// marker-space table built on one and on two threads gives the same trajectory, byte for byte.
TEST(Determinism, HooverMillerIsTheSameForOneAndTwoThreads) {
  const std::string args = "experiment hoover-miller --grid 32 --cycles 1 --set coupling.threads=";
  const std::string one = hash_of(args + "1", "trajectory.csv", "determinism_hm1");
  const std::string two = hash_of(args + "2", "trajectory.csv", "determinism_hm2");
  ASSERT_EQ(one.size(), 64u);
  EXPECT_EQ(one, two);
}

// The SPH larva evaluates its particles on a thread pool: one and two threads give the same bytes.
TEST(Determinism, LarvaFramesAreTheSameForOneAndTwoThreads) {
  const std::string one = hash_of("experiment mosquito-larva --set run.threads=1", "frames.csv", "determinism_larva1");
  const std::string two = hash_of("experiment mosquito-larva --set run.threads=2", "frames.csv", "determinism_larva2");
  ASSERT_EQ(one.size(), 64u);
  EXPECT_EQ(one, two);
  if (kOptimisedBuild) {
    EXPECT_EQ(one, recorded("mosquito-larva/frames.csv"));
  }
}

}  // namespace
}  // namespace jellysim
