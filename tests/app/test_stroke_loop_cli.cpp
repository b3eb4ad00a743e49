// `jellysim run --loop CYCLES` / render.loop (issue 39 item 3): a coarse tank whose stroke repeats
// from its second cycle, so each run is a second or so.
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../cli_runner.hpp"

namespace cli = jellysim::testing;
namespace fs = std::filesystem;

namespace {

/// 48 x 96 cells (the bell 8 cells across), 160 x 120 PNG frames and nothing else rendered. The
/// tentacles continue the margin (jellyfish.tentacle_root = "margin"): on this grid they then fold
/// across the aperture in every stroke and the stroke repeats from the second cycle; with the
/// default root the bell keeps speeding up for several cycles (the loop's speed mismatch at cycle 2
/// measured 0.15), like the converged bell.
const std::string kLoopRun =
    "run --quiet --set tank.cells=[48,96] --set render.width=160 --set render.height=120 --set render.video=false "
    "--set render.glb=false --set render.viewer=false --set render.pc2=false --set jellyfish.tentacle_root=\"margin\"";

struct Point {
  double x = 0.0, y = 0.0;
};

/// loop_slices.csv's umbrella points by frame.
std::map<int, std::vector<Point>> loop_umbrellas(const fs::path& dir, std::map<int, double>* times = nullptr) {
  std::istringstream text(cli::read_text_file(dir / "loop_slices.csv"));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "part,frame,t,index,x,y");
  std::map<int, std::vector<Point>> frames;
  while (std::getline(text, line)) {
    if (line.rfind("umbrella,", 0) != 0) continue;
    std::istringstream row(line.substr(9));
    double frame = 0, t = 0, index = 0;
    Point p;
    char comma = 0;
    row >> frame >> comma >> t >> comma >> index >> comma >> p.x >> comma >> p.y;
    frames[static_cast<int>(frame)].push_back(p);
    if (times) (*times)[static_cast<int>(frame)] = t;
  }
  return frames;
}

/// RMS distance between the points of two frames, over the bell diameter (4 cm).
double rms_over_diameter(const std::vector<Point>& a, const std::vector<Point>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::pow(b[i].x - a[i].x, 2) + std::pow(b[i].y - a[i].y, 2);
  return std::sqrt(sum / static_cast<double>(a.size())) / 0.04;
}

}  // namespace

TEST(LoopCli, TheLoopsFirstFrameMatchesTheFrameOneLoopLater) {
  const fs::path dir = cli::fresh_scratch_dir("loop_remove");
  const cli::CliResult r = cli::run_jellysim(kLoopRun + " --loop 1 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  const auto& loop = s["loop"];
  // 30 frames/s at 0.7 Hz rounded to 43 frames a cycle; cycle 2's start matches cycle 1's.
  EXPECT_EQ(loop["frames_per_cycle"], 43);
  EXPECT_EQ(s["fps"].get<double>(), 43 * 0.7);
  EXPECT_EQ(loop["periodic_cycle"], 2);
  EXPECT_EQ(loop["first_frame"], 86);
  EXPECT_EQ(loop["frames"], 43);
  EXPECT_LE(loop["mismatch"]["shape"].get<double>(), 0.05);
  EXPECT_LE(loop["mismatch"]["speed"].get<double>(), 0.05);
  // The run stopped once the loop and the frame after its closing frame were recorded.
  EXPECT_EQ(s["frames"], 3 * 43 + 2);
  EXPECT_EQ(s["animation"]["frames"], 43);
  EXPECT_TRUE(fs::exists(dir / "frames/frame_0042.png"));
  EXPECT_FALSE(fs::exists(dir / "frames/frame_0043.png"));
  // The frame after the last (43) is the first (0) within the measured closure, which is within
  // the tolerance; the root motion is gone (the centroids agree), so the RMS of the points is the
  // shape mismatch itself.
  std::map<int, double> t;
  const auto frames = loop_umbrellas(dir, &t);
  ASSERT_EQ(frames.size(), 44u);
  for (int k = 0; k <= 43; ++k) EXPECT_EQ(t[k], k / (43 * 0.7)) << k;
  const double closure = loop["closure"]["shape"].get<double>();
  EXPECT_NEAR(rms_over_diameter(frames.at(0), frames.at(43)), closure, 1e-9);
  EXPECT_LE(closure, 0.05);
  EXPECT_LE(loop["closure"]["speed"].get<double>(), 0.05);
  // Without the root motion removed the closing frame would sit a cycle's travel further on (2 mm
  // on this coarse tank), several times the closure.
  const double travel = loop["travel"][1].get<double>();
  EXPECT_GT(travel / 0.04, 5 * closure);
  fs::remove_all(dir);
}

TEST(LoopCli, ConstantRootMotionMovesTheClosingFrameByTheTravel) {
  const fs::path dir = cli::fresh_scratch_dir("loop_constant");
  const cli::CliResult r = cli::run_jellysim(kLoopRun + " --loop 1 --set render.loop_root_motion=constant "
                                                        "--set render.png_frames=false --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  const double travel = s["loop"]["travel"][1].get<double>();
  const auto frames = loop_umbrellas(dir);
  std::vector<Point> moved_back = frames.at(43);
  for (Point& p : moved_back) p.y -= travel;
  EXPECT_NEAR(rms_over_diameter(frames.at(0), moved_back), s["loop"]["closure"]["shape"].get<double>(), 1e-9);
  EXPECT_NEAR(s["loop"]["root_velocity"][1].get<double>(), travel / (43 / (43 * 0.7)), 1e-15);
  fs::remove_all(dir);
}

TEST(LoopCli, AStrokeThatDoesNotRepeatInTimeFailsNamingTheTolerance) {
  const fs::path dir = cli::fresh_scratch_dir("loop_never");
  const cli::CliResult r = cli::run_jellysim(kLoopRun + " --loop 1 --set render.loop_tolerance=1e-6 "
                                                        "--set render.loop_max_cycles=3 --set render.png_frames=false "
                                                        "--out " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  EXPECT_EQ(s["status"], "failed");
  EXPECT_NE(s["failure"].get<std::string>().find("render.loop_tolerance"), std::string::npos) << s["failure"];
  EXPECT_EQ(s["loop"]["periodic_cycle"], 0);
  EXPECT_EQ(s["loop"]["checked"].size(), 2u);   // cycles 2 and 3
  EXPECT_EQ(s["frames"], (3 + 1) * 43 + 2);     // run to the cap
  fs::remove_all(dir);
}

TEST(LoopCli, BadLoopSettingsAreRefusedNamingTheOption) {
  const fs::path dir = cli::fresh_scratch_dir("loop_bad");
  fs::create_directories(dir.parent_path());
  const fs::path scene = dir.parent_path() / "loop_bad_scene.toml";  // a loop needs the tank to itself
  std::ofstream(scene) << "scene = \"jellyfish\"\n[[objects]]\ntype = \"circle\"\ncentre = [0.12, 0.25]\nradius = 0.02\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run --loop 0", "--loop"},
      {"run --loop -1", "--loop"},
      {"run --loop 101", "--loop"},
      {"run --loop nan", "--loop"},
      {"run --set render.loop_tolerance=0", "render.loop_tolerance"},
      {"run --set render.loop_tolerance=nan", "render.loop_tolerance"},
      {"run --set render.loop_max_cycles=1", "render.loop_max_cycles"},
      {"run --set render.loop_root_motion=keep", "render.loop_root_motion"},
      {"run " + scene.string() + " --loop 1", "render.loop"},
  };
  for (const auto& [args, option] : cases) {
    const cli::CliResult r = cli::run_jellysim(args + " --quiet --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "summary.json")) << args;
  }
  fs::remove_all(dir);
  fs::remove(scene);
}
