// `jellysim run --loop CYCLES` / render.loop (issue 39 item 3): a coarse tank whose stroke repeats
// from its second cycle, so each run is a second or so.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../cli_runner.hpp"
#include "jellysim/io/mesh_files.hpp"

namespace cli = jellysim::testing;
namespace fs = std::filesystem;

namespace {

/// 48 x 96 cells (the bell 8 cells across), 160 x 120 PNG frames and nothing else rendered. On this
/// grid a one-cycle loop closes at cycle 3 (cycle 2's start against cycle 3's: shape 0.039, speed
/// 0.041 of the tolerance's 0.05; cycle 1 against 2 misses by speed, 0.116).
const std::string kLoopRun =
    "run --quiet --set tank.cells=[48,96] --set render.width=160 --set render.height=120 --set render.video=false "
    "--set render.glb=false --set render.viewer=false --set render.pc2=false";

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

/// Where accessor `index` of a .glb starts in its binary chunk, and its element count.
std::pair<const char*, std::size_t> accessor_data(const jellysim::io::GlbContents& glb, std::size_t index) {
  const nlohmann::json& a = glb.json["accessors"][index];
  const nlohmann::json& view = glb.json["bufferViews"][a["bufferView"].get<std::size_t>()];
  return {glb.bin.data() + view["byteOffset"].get<std::size_t>() + a.value("byteOffset", 0), a["count"].get<std::size_t>()};
}

/// The float values of a glTF accessor (its elements one after another), as doubles.
std::vector<double> float_accessor(const jellysim::io::GlbContents& glb, std::size_t index) {
  const auto [data, count] = accessor_data(glb, index);
  const std::string& type = glb.json["accessors"][index]["type"];
  std::vector<float> v((type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4) * count);
  std::memcpy(v.data(), data, 4 * v.size());
  return {v.begin(), v.end()};
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
  // The check is the loop's own closure: cycle 3's start against cycle 2's, so the loop is cycle 2.
  EXPECT_EQ(loop["periodic_cycle"], 3);
  EXPECT_EQ(loop["start_cycle"], 2);
  EXPECT_EQ(loop["first_frame"], 86);
  EXPECT_EQ(loop["frames"], 43);
  EXPECT_LE(loop["mismatch"]["shape"].get<double>(), 0.05);
  EXPECT_LE(loop["mismatch"]["speed"].get<double>(), 0.05);
  EXPECT_EQ(loop["closure"], loop["mismatch"]);
  EXPECT_GT(loop["checked"][0]["speed"].get<double>(), 0.05);  // cycle 1's loop would not have closed
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
  EXPECT_EQ(s["loop"]["checked"].size(), 2u);  // closing cycles 2 and 3
  EXPECT_EQ(s["frames"], 3 * 43 + 2);          // run to the cap: cycle 3's start and the frame after it
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
      {"run --loop 3 --set render.loop_max_cycles=3", "render.loop_cycles"},
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

// The .glb of a loop ends with its closing key: frame 0 again one frame after the last, so that a
// player looping the clip over its duration (three.js in viewer.html) wraps without a jump. Its
// morph weights are all 0 (the base: frame 0's shape); with the root motion kept the root moves on
// by the loop's travel, and its last step is one of the loop's ordinary steps (the slice plane is
// the 3D z = 0 plane); frame_count says the frames to play (43), without the closing key.
TEST(LoopCli, TheGlbEndsWithTheClosingKeySoThatItLoopsWithoutAJump) {
  const fs::path dir = cli::fresh_scratch_dir("loop_glb");
  const cli::CliResult r = cli::run_jellysim(kLoopRun + " --loop 1 --set render.loop_root_motion=constant "
                                                        "--set render.glb=true --set render.png_frames=false --out " +
                                             dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(cli::read_text_file(dir / "summary.json"));
  const jellysim::io::GlbContents glb = jellysim::io::parse_glb(cli::read_text_file(dir / "jellyfish.glb"));
  EXPECT_EQ(glb.json["asset"]["extras"]["frame_count"], 43);
  EXPECT_EQ(glb.json["asset"]["extras"]["loop"], true);
  const nlohmann::json& swim = glb.json["animations"][0];
  std::vector<double> roots, times;
  std::size_t weight_keys = 0;
  const std::uint8_t* last_weights = nullptr;
  const std::size_t targets = glb.json["meshes"][0]["weights"].size();
  for (const auto& channel : swim["channels"]) {
    const auto& sampler = swim["samplers"][channel["sampler"].get<std::size_t>()];
    if (channel["target"]["node"] == 0 && channel["target"]["path"] == "translation") {  // the jellyfish's root
      roots = float_accessor(glb, sampler["output"]);
      times = float_accessor(glb, sampler["input"]);
    }
    if (channel["target"]["node"] == 1 && channel["target"]["path"] == "weights") {  // its mesh's morph weights
      weight_keys = accessor_data(glb, sampler["input"]).second;
      last_weights = reinterpret_cast<const std::uint8_t*>(accessor_data(glb, sampler["output"]).first) +
                     (weight_keys - 1) * targets;
    }
  }
  ASSERT_EQ(times.size(), 44u);
  EXPECT_FLOAT_EQ(static_cast<float>(times.back()), static_cast<float>(1.0 / 0.7));  // 43 frames of 1 / (43 · 0.7) s
  ASSERT_EQ(roots.size(), 3 * 44u);
  EXPECT_NEAR(roots[3 * 43] - roots[0], s["loop"]["travel"][0].get<double>(), 1e-6);
  EXPECT_NEAR(roots[3 * 43 + 1] - roots[1], s["loop"]["travel"][1].get<double>(), 1e-6);
  EXPECT_EQ(roots[3 * 43 + 2], roots[2]);
  double largest_step = 0.0;
  for (std::size_t k = 0; k + 1 < 43; ++k)
    largest_step = std::max(largest_step, std::hypot(roots[3 * k + 3] - roots[3 * k], roots[3 * k + 4] - roots[3 * k + 1]));
  EXPECT_LE(std::hypot(roots[3 * 43] - roots[3 * 42], roots[3 * 43 + 1] - roots[3 * 42 + 1]), largest_step);
  ASSERT_NE(last_weights, nullptr);
  EXPECT_EQ(weight_keys, targets + 2);  // frame 0, each target, the closing key
  for (std::size_t t = 0; t < targets; ++t) EXPECT_EQ(last_weights[t], 0) << t;
  fs::remove_all(dir);
}
