// End-to-end tests of `jellysim view` (docs/viewer.md): the viewer runs under a virtual X display
// (xvfb-run, Mesa's software OpenGL) with scripted input events; the test checks the screenshot
// is a real picture and that the state changed as the input asked (stats JSON with a timeline).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <set>

#include "../cli_runner.hpp"
#include "jellysim/render/image.hpp"

namespace {

using jellysim::testing::fresh_scratch_dir;
using jellysim::testing::read_text_file;
using jellysim::testing::run_jellysim;

bool have_xvfb_run() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

/// Runs the viewer on a virtual display.
jellysim::testing::CliResult run_viewer_headless(const std::string& args) {
  const std::string xvfb = "xvfb-run -a -s '-screen 0 1280x720x24' ";
  // Under the sanitizers, leak checking is off for the viewer process only: Mesa's software driver
  // is dlopen'ed and unloaded at exit, so LeakSanitizer reports its allocations from an "unknown
  // module" that no suppression can name. Memory errors and undefined behaviour are still fatal.
  const std::string no_driver_leaks = "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\" ";
  const std::string cmd = no_driver_leaks + xvfb + JELLYSIM_CLI_PATH + " view " + args + " 2>&1";
  jellysim::testing::CliResult r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The scripted tests run on the thesis's 80 cm tank (scenes/jellyfish-thesis.toml: quick under the
// sanitizers, and the screen positions below are laid out for it).
const std::string kThesisScene = std::string(JELLYSIM_SOURCE_DIR) + "/scenes/jellyfish-thesis.toml";
const char* kThesisTank = "[tank]\nwidth = 0.8\nheight = 0.8\ncells = [60, 60]\n";

// The 1280 × 720 layout the scripted tests ask for: controls 330 px on the right, the 2D panel in the left half of
// the rest (475 px), the tank fitted into it with a 4 px margin (docs/viewer.md).
constexpr double kScalePxPerM = (475.0 - 8.0) / 0.8;
constexpr double kTankTopPx = 4.0 + 0.5 * (712.0 - 467.0);
double screen_x(double x_m) { return 4.0 + x_m * kScalePxPerM; }
double screen_y(double y_m) { return kTankTopPx + (0.8 - y_m) * kScalePxPerM; }

const nlohmann::json& timeline_entry(const nlohmann::json& stats, const std::string& event) {
  for (const auto& e : stats["timeline"]) {
    if (e["event"] == event) return e;
  }
  throw std::runtime_error("no timeline entry for '" + event + "'");
}

TEST(Viewer, ScriptedInputUnderXvfbChangesTheStateAndDrawsAPicture) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_scripted");
  std::filesystem::create_directories(dir);
  // The thesis scene's jellyfish has its apex at (0.4, 0.328) m: grab it there and drag it 0.1 m right.
  const double x0 = screen_x(0.4), y0 = screen_y(0.328), x1 = screen_x(0.5);
  const std::string script = "5 pause\n"
                             "8 mark paused\n"
                             "10 drag " + std::to_string(x0) + " " + std::to_string(y0) + " " + std::to_string(x1) +
                             " " + std::to_string(y0) + " 10\n"
                             "22 mark dragged\n"
                             "23 set frequency 0 1.3; 23 set viscosity 2e-5; 23 set noise.unstructured 0.9\n"
                             "24 pause\n"
                             "40 drag 100 200 160 200 5  # stir the water\n"
                             "55 mark running\n";
  std::ofstream(dir / "input.txt") << script;
  const auto r = run_viewer_headless(kThesisScene + " --width 1280 --height 720 --frames 60 --fps 0 --script " +
                                     (dir / "input.txt").string() +
                                     " --screenshot " + (dir / "shot.png").string() + " --stats " +
                                     (dir / "stats.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_text_file(dir / "stats.json"));
  EXPECT_EQ(stats["frames"], 60);
  EXPECT_GT(stats["steps"].get<long>(), 0);
  EXPECT_GT(stats["fps"].get<double>(), 0.0);
  EXPECT_GT(stats["sim_rate"].get<double>(), 0.0);
  EXPECT_EQ(stats["failure"], "");

  // Pausing stopped simulated time.
  const auto& paused_at = timeline_entry(stats, "5 pause");
  const auto& still_paused = timeline_entry(stats, "8 mark paused");
  EXPECT_TRUE(still_paused["paused"].get<bool>());
  EXPECT_EQ(paused_at["time_s"].get<double>(), still_paused["time_s"].get<double>());
  EXPECT_EQ(paused_at["steps"], still_paused["steps"]);

  // The drag moved jellyfish 0 by the dragged distance (0.1 m right), while paused.
  const auto before = still_paused["jellyfish"][0]["centroid_m"];
  const auto after = timeline_entry(stats, "22 mark dragged")["jellyfish"][0]["centroid_m"];
  EXPECT_NEAR(after[0].get<double>() - before[0].get<double>(), 0.1, 2e-3);
  EXPECT_NEAR(after[1].get<double>() - before[1].get<double>(), 0.0, 2e-3);
  // The default scene keeps its mirror symmetry until the sideways drag breaks it.
  EXPECT_TRUE(still_paused["mirror_symmetry"].get<bool>());
  EXPECT_FALSE(timeline_entry(stats, "22 mark dragged")["mirror_symmetry"].get<bool>());

  // The parameters took effect, and the simulation ran on after the second pause toggle.
  const auto& state = stats["state"];
  EXPECT_EQ(state["jellyfish"][0]["frequency_hz"].get<double>(), 1.3);
  EXPECT_EQ(state["viscosity"].get<double>(), 2e-5);
  EXPECT_EQ(state["noise"]["unstructured"].get<double>(), 0.9);
  EXPECT_FALSE(state["paused"].get<bool>());
  EXPECT_GT(timeline_entry(stats, "55 mark running")["time_s"].get<double>(), paused_at["time_s"].get<double>());

  // The screenshot is a picture: many colours and real contrast.
  const auto image = jellysim::render::read_png(dir / "shot.png");
  ASSERT_EQ(image.width, 1280);
  ASSERT_EQ(image.height, 720);
  std::set<int> colours;
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t k = 0; k + 2 < image.pixels.size(); k += 3) {
    colours.insert(image.pixels[k] << 16 | image.pixels[k + 1] << 8 | image.pixels[k + 2]);
    const double lum = 0.3 * image.pixels[k] + 0.59 * image.pixels[k + 1] + 0.11 * image.pixels[k + 2];
    sum += lum;
    sum2 += lum * lum;
  }
  const double n = static_cast<double>(image.pixels.size() / 3);
  const double stddev = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  EXPECT_GT(colours.size(), 200u);
  EXPECT_GT(stddev, 10.0);
  // The 3D panel (x in [475, 950)) shows the jellyfish over the water: not one flat colour.
  std::set<int> panel_colours;
  for (int y = 100; y < 620; ++y) {
    for (int x = 500; x < 925; ++x) {
      const auto c = image.at(x, y);
      panel_colours.insert(c[0] << 16 | c[1] << 8 | c[2]);
    }
  }
  EXPECT_GT(panel_colours.size(), 50u);
}

// An axisymmetric tank in the viewer (issue 22): the ring bell keeps its symmetry through every
// edit — a diagonal drag moves it along the axis only, stirring makes a ring, a right-click
// (steering) is ignored — and it swims on.
TEST(Viewer, AxisymmetricBellStaysOnItsAxis) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_axisymmetric");
  std::filesystem::create_directories(dir);
  const std::string events = "2 pause; 3 drag " + std::to_string(screen_x(0.4)) + " " + std::to_string(screen_y(0.328)) +
                             " " + std::to_string(screen_x(0.5)) + " " + std::to_string(screen_y(0.378)) +
                             " 5; 10 mark moved; 11 pause; 12 drag 100 200 160 200 5; 20 press " +
                             std::to_string(screen_x(0.6)) + " " + std::to_string(screen_y(0.6)) + " right; 21 release " +
                             std::to_string(screen_x(0.6)) + " " + std::to_string(screen_y(0.6)) + " right; 40 mark swum";
  const auto r = run_viewer_headless(kThesisScene +
                                     " --set tank.geometry=axisymmetric --width 1280 --height 720 --frames 42 --fps 0"
                                     " --inject \"" + events + "\" --stats " + (dir / "stats.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_text_file(dir / "stats.json"));
  EXPECT_EQ(stats["failure"], "");
  const auto before = timeline_entry(stats, "2 pause")["jellyfish"][0]["centroid_m"];
  const auto moved = timeline_entry(stats, "10 mark moved");
  EXPECT_NEAR(moved["jellyfish"][0]["centroid_m"][0].get<double>(), before[0].get<double>(), 1e-12);
  EXPECT_NEAR(moved["jellyfish"][0]["centroid_m"][1].get<double>() - before[1].get<double>(), 0.05, 2e-3);
  const auto& swum = timeline_entry(stats, "40 mark swum");
  EXPECT_TRUE(swum["mirror_symmetry"].get<bool>());
  EXPECT_NEAR(swum["jellyfish"][0]["centroid_m"][0].get<double>(), before[0].get<double>(), 1e-12);
  EXPECT_GT(swum["time_s"].get<double>(), moved["time_s"].get<double>());
}

TEST(Viewer, DraggingAnObstacleMovesIt) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_obstacle");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.toml") << "scene = \"jellyfish\"\n" << kThesisTank
                                    << "[jellyfish]\nposition = [0.4, 0.3]\n[[objects]]\ntype = \"circle\"\n"
                                       "centre = [0.2, 0.6]\nradius = 0.04\n";
  const std::string drag = "2 pause; 3 drag " + std::to_string(screen_x(0.2)) + " " + std::to_string(screen_y(0.6)) +
                           " " + std::to_string(screen_x(0.3)) + " " + std::to_string(screen_y(0.55)) +
                           " 5; 10 mark moved";
  const auto r = run_viewer_headless((dir / "scene.toml").string() + " --width 1280 --height 720 --frames 12 --fps 0 --inject \"" + drag +
                                     "\" --stats " + (dir / "stats.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_text_file(dir / "stats.json"));
  const auto before = timeline_entry(stats, "2 pause")["obstacles"][0]["centroid_m"];
  const auto after = timeline_entry(stats, "10 mark moved")["obstacles"][0]["centroid_m"];
  EXPECT_NEAR(after[0].get<double>() - before[0].get<double>(), 0.1, 2e-3);
  EXPECT_NEAR(after[1].get<double>() - before[1].get<double>(), -0.05, 2e-3);
}

// The 3D panel draws obstacles as opaque prisms (docs/viewer.md): two jellyfish 0.2 m apart frame a
// view in which a 4 cm box between them must appear. The same scene without the box, paused at
// t = 0 so that both pictures show the same state, differs from it only where the box is drawn.
// The framing keeps both jellyfish whole in the tall panel: its side columns show only water.
// The translucent shell in the 3D panel is one smooth layer: drawn in mesh order, far triangles
// blended over near ones put dark saw-teeth along its outline (pixels far darker than the rest of
// their row of the shell). Counted in the built-in scene's first frame, the bell large in the panel:
// 777 such pixels before the fix, 154 after (the rim's shading), in this 1280 x 720 window.
TEST(Viewer, TheShellHasNoDarkSawTeethAlongItsOutline) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_shell");
  std::filesystem::create_directories(dir);
  const auto r = run_viewer_headless("--width 1280 --height 720 --3d-scale 1 --frames 2 --fps 0 --inject \"0 pause\" "
                                     "--screenshot " + (dir / "shell.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto image = jellysim::render::read_png(dir / "shell.png");
  ASSERT_EQ(image.width, 1280);
  const auto brightness = [&](int x, int y) {
    const auto p = image.at(x, y);
    return p[0] + p[1] + p[2];
  };
  const int water = brightness(480, 5);
  // Per row of the 3D panel (x in [480, 940)) wide enough to be the bell's: pixels between its
  // first and last clearly-not-water pixel that are below 70 % of the row's median brightness but
  // not water seen through the open aperture.
  int dark = 0, shell_rows = 0;
  for (int y = 0; y < 720; ++y) {
    std::vector<int> row;
    int first = -1, last = -1;
    for (int x = 480; x < 940; ++x)
      if (brightness(x, y) > water + 60) {
        if (first < 0) first = x;
        last = x;
      }
    if (first < 0 || last - first < 40) continue;
    for (int x = first; x <= last; ++x) row.push_back(brightness(x, y));
    std::vector<int> sorted = row;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const int median = sorted[sorted.size() / 2];
    ++shell_rows;
    for (int b : row) dark += (b < 0.7 * median && b > water + 25) ? 1 : 0;
  }
  EXPECT_GT(shell_rows, 100) << "the bell should fill a good part of the panel";
  EXPECT_LT(dark, 300) << "dark saw-teeth along the shell";
}

// Marine snow: the tracers appear as specks in the 3D panel around the bell (none without tracers).
// Counted in the panel's top 120 rows, above the bell: 192 bright pixels measured, 0 without.
TEST(Viewer, MarineSnowSpecksTheWaterAroundTheBell) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_snow");
  std::filesystem::create_directories(dir);
  int bright[2] = {0, 0};
  for (int with = 0; with < 2; ++with) {
    const auto png = dir / (with ? "snow.png" : "none.png");
    const auto r = run_viewer_headless(std::string(with ? "" : "--set tank.tracers_per_side=0 ") +
                                       "--width 1280 --height 720 --3d-scale 1 --frames 2 --fps 0 --inject \"0 pause\" "
                                       "--screenshot " + png.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto image = jellysim::render::read_png(png);
    const auto water = image.at(480, 5);
    for (int y = 0; y < 120; ++y)
      for (int x = 480; x < 940; ++x) {
        const auto p = image.at(x, y);
        bright[with] += p[0] + p[1] + p[2] > water[0] + water[1] + water[2] + 120 ? 1 : 0;
      }
  }
  EXPECT_EQ(bright[0], 0);
  EXPECT_GT(bright[1], 100);
}

TEST(Viewer, ObstaclesAppearAsPrismsInThe3DPanel) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_prisms");
  std::filesystem::create_directories(dir);
  // No tracers: their marine snow would speck the panel's edges checked below.
  const std::string two_jellyfish = "scene = \"jellyfish\"\n" + std::string(kThesisTank) + "tracers_per_side = 0\n" +
                                    "[jellyfish]\nposition = [0.3, 0.3]\n"
                                    "[[objects]]\ntype = \"jellyfish\"\nposition = [0.5, 0.3]\n";
  std::ofstream(dir / "box.toml") << two_jellyfish << "[[objects]]\ntype = \"box\"\ncentre = [0.4, 0.3]\nsize = [0.04, 0.04]\n";
  std::ofstream(dir / "none.toml") << two_jellyfish;
  for (const std::string name : {"box", "none"}) {
    const auto r = run_viewer_headless((dir / (name + ".toml")).string() +
                                       " --width 1280 --height 720 --frames 2 --fps 0 --inject \"0 pause\" --screenshot " +
                                       (dir / (name + ".png")).string());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.output;
  }
  const auto with_box = jellysim::render::read_png(dir / "box.png");
  const auto without = jellysim::render::read_png(dir / "none.png");
  ASSERT_EQ(with_box.width, 1280);
  ASSERT_EQ(with_box.height, 720);
  ASSERT_EQ(without.width, 1280);
  ASSERT_EQ(without.height, 720);
  const auto difference = [](const jellysim::render::Rgb& a, const jellysim::render::Rgb& b) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
  };
  // Pixels of the 3D panel (x in [475, 950)) that differ (the dark box from the dark water by 20–60
  // in the sum of channels over most of its face; identical renders by 0), inside the middle of the panel
  // (between the two jellyfish, where the box is) and outside it.
  int inside = 0, outside = 0, inside_total = 0;
  for (int y = 0; y < 720; ++y) {
    for (int x = 475; x < 950; ++x) {
      const bool middle = x >= 650 && x < 770 && y >= 335 && y < 425;
      inside_total += middle ? 1 : 0;
      if (difference(with_box.at(x, y), without.at(x, y)) > 20) ++(middle ? inside : outside);
    }
  }
  EXPECT_GT(inside, inside_total * 4 / 5) << "the box's prism should cover the middle of the panel";
  EXPECT_GT(inside + outside, 12000);
  EXPECT_LT(outside, inside) << "away from the box the two pictures should mostly agree";
  // Nothing but water in the panel's outer 10 px columns: no jellyfish is cut off at the sides.
  const auto water = without.at(480, 5);
  int cut = 0;
  for (int y = 0; y < 720; ++y) {
    for (int x : {476, 478, 480, 482, 484, 940, 942, 944, 946, 948}) cut += difference(without.at(x, y), water) > 12 ? 1 : 0;
  }
  EXPECT_EQ(cut, 0);
}

TEST(Viewer, BadScriptIsAnInputErrorNamingTheLine) {
  const auto r = run_jellysim("view --frames 1 --inject \"3 pause; 4 jump 1 2\"");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--inject, line 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown event 'jump'"), std::string::npos) << r.output;
  const auto range = run_jellysim("view --frames 1 --inject \"3 set gamma 0 1.5\"");
  EXPECT_EQ(range.exit_code, 2) << range.output;
  EXPECT_NE(range.output.find("gamma must be in (0, 1]"), std::string::npos) << range.output;
}

TEST(Viewer, OptionOutOfRangeIsRejected) {
  const auto r = run_jellysim("view --width 10");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--width"), std::string::npos) << r.output;
}

}  // namespace

// Issue 39's viewer defects: the 3D panel drawn multisampled (antialiased edges; specks thinner than
// a pixel covered in part instead of sparkling), the 2D panel with a colour bar for its field (the
// vorticity map from +range at the top to −range at the bottom, in the tank's top-right corner) and
// the tracers in a green that no colour of the maps comes near. Thesis tank, 1280 × 720: the bar's
// column x = 458 runs from y = 137 to 276; measured (254, 200, 125) at the top, (8, 15, 36) in the
// middle, (140, 204, 255) at the bottom; 4 samples per pixel on llvmpipe; the outline blended.
TEST(Viewer, The3DPanelIsMultisampledAndThe2DPanelHasAColourBar) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_colour_bar");
  std::filesystem::create_directories(dir);
  const auto r = run_viewer_headless(kThesisScene + " --width 1280 --height 720 --frames 3 --fps 0 --paused --screenshot " +
                                     (dir / "shot.png").string() + " --stats " + (dir / "stats.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_text_file(dir / "stats.json"));
  EXPECT_GE(stats["msaa_samples"].get<int>(), 2);
  EXPECT_EQ(stats["steps"], 0);  // paused: the picture does not depend on how busy the machine is
  const auto image = jellysim::render::read_png(dir / "shot.png");
  ASSERT_EQ(image.width, 1280);
  const auto off = [&](int x, int y, std::array<int, 3> want) {
    const auto p = image.at(x, y);
    return std::abs(p[0] - want[0]) + std::abs(p[1] - want[1]) + std::abs(p[2] - want[2]);
  };
  EXPECT_LT(off(458, 137, {255, 204, 128}), 15) << "the warm end (+range) at the bar's top";
  EXPECT_LT(off(458, 206, {8, 15, 36}), 15) << "dark water (0) in its middle";
  EXPECT_LT(off(458, 276, {140, 204, 255}), 15) << "the cold end (−range) at its bottom";
  // Antialiased outline: on rows crossing the bell in the 3D panel (x in [476, 948)), the pixel just
  // outside its silhouette (the first pixel 60 above the water's brightness) carries more than 8 %
  // of the step to the bell's brightness in 60 of 154 rows at 4 samples, in 22 of 146 rows with the
  // single-sample panel of before this change (its shader differed too). Since 2026-11-28 the viewer
  // is paused (t = 0): 51 rows, whatever the load (running, the steps per frame followed the wall
  // clock, and a loaded suite once counted 44).
  const auto brightness = [&](int x, int y) {
    const auto p = image.at(x, y);
    return p[0] + p[1] + p[2];
  };
  const int water = brightness(480, 5);
  int blended_rows = 0;
  for (int y = 100; y < 650; y += 2) {
    int first = -1, count = 0;
    for (int x = 476; x < 948; ++x)
      if (brightness(x, y) > water + 60) {
        first = first < 0 ? x : first;
        ++count;
      }
    if (count < 20) continue;
    int inner = 0;
    for (int k = 0; k < 4; ++k) inner = std::max(inner, brightness(first + k, y));
    blended_rows += brightness(first - 1, y) - water > 0.08 * (inner - water) ? 1 : 0;
  }
  std::printf("  blended rows %d\n", blended_rows);
  EXPECT_GT(blended_rows, 45) << "the bell's outline should be blended into the water";
  // Green-dominant pixels (G above R and B by 80; no colour of either map is): the tracers, drawn
  // at 2/3 opacity over the field.
  int tracer_pixels = 0;
  for (int y = 130; y < 590; ++y)
    for (int x = 8; x < 440; ++x) {
      const auto p = image.at(x, y);
      tracer_pixels += p[1] > p[0] + 80 && p[1] > p[2] + 80 ? 1 : 0;
    }
  EXPECT_GT(tracer_pixels, 4500) << "the tracers in their green (5816 measured; 0 when they were white)";
}

// `jellysim view` on a 3D scene (docs/viewer.md "The 3D scene"): the shell bell stepped live in a
// tiny 3D tank (10 cm a side, 16 cells, the quarter tank), a coupled step per frame at --fps 0;
// the stats say 3D, the bell rose upright on its axis, and the screenshot holds the wake's colours
// beside the bell.
TEST(Viewer, TheThreeDimensionalBellSwimsInTheViewer) {
  if (!have_xvfb_run()) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const auto dir = fresh_scratch_dir("viewer_3d");
  std::filesystem::create_directories(dir);
  const std::string scene = std::string(JELLYSIM_SOURCE_DIR) + "/scenes/jellyfish-3d.toml";
  const auto r = run_viewer_headless(scene + " --set tank.size=[0.1,0.1,0.1] --set tank.cells=[16,16,16]"
                                     " --set jellyfish.position=[0,0.03] --set jellyfish.tentacle_length=0.005"
                                     " --width 960 --height 540 --frames 12 --fps 0 --stats " + (dir / "stats.json").string() +
                                     " --screenshot " + (dir / "shot.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_text_file(dir / "stats.json"));
  EXPECT_EQ(stats["failure"], "");
  EXPECT_EQ(stats["geometry"], "3d");
  EXPECT_EQ(stats["steps"], 12);  // one coupled step a frame at --fps 0
  const auto& c = stats["state"]["centroid"];
  // The surface's centroid starts 42.66 mm up (12.7 mm above the aperture); measured 42.91 mm after
  // 12 steps (0.060 s): it rose 0.25 mm.
  EXPECT_GT(c[1].get<double>(), 0.04281);
  EXPECT_LT(c[1].get<double>(), 0.04301);
  EXPECT_NEAR(c[0].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(stats["state"]["tilt_deg"].get<double>(), 0.0, 1e-6);
  const jellysim::render::RgbImage shot = jellysim::render::read_png(dir / "shot.png");
  ASSERT_EQ(shot.width, 960);
  std::set<std::array<std::uint8_t, 3>> colours;
  for (std::size_t k = 0; k + 2 < shot.pixels.size(); k += 3)
    colours.insert({shot.pixels[k], shot.pixels[k + 1], shot.pixels[k + 2]});
  EXPECT_GT(colours.size(), 200u);  // a picture, not a blank window
  std::filesystem::remove_all(dir);
}
