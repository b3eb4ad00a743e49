// `jellysim experiment resonance` on the coarsest tank (docs/control.md): the release test finds a
// natural frequency, the sweep around it writes resonance.csv and the summary's three figures.
#include "../cli_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

TEST(ResonanceCli, ReleaseTestAndSweepWriteTheirFiles) {
  const fs::path dir = jellysim::testing::fresh_scratch_dir("resonance");
  const auto r = jellysim::testing::run_jellysim(
      "experiment resonance --out " + dir.string() +
      " --set tank.cells=[48,96] --set resonance.multiples=[0.5,1.0] --set resonance.cycles=2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = nlohmann::json::parse(jellysim::testing::read_text_file(dir / "summary.json"));
  ASSERT_TRUE(s["natural_frequency_hz"].is_number()) << s.dump();
  EXPECT_GT(s["natural_frequency_hz"].get<double>(), 0.5);  // the coarse bell rings at a few hertz
  EXPECT_TRUE(s["fastest_frequency_hz"].is_number());
  EXPECT_TRUE(s["cheapest_frequency_hz"].is_number());
  const std::string csv = jellysim::testing::read_text_file(dir / "resonance.csv");
  EXPECT_EQ(csv.rfind("frequency,speed,cost_of_transport", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  for (const char* file : {"ringdown.csv", "resonance.png"}) EXPECT_TRUE(fs::exists(dir / file)) << file;
  fs::remove_all(dir);
}

TEST(ResonanceCli, AnEmptySweepIsExit2NamingTheField) {
  const fs::path dir = jellysim::testing::fresh_scratch_dir("resonance_bad");
  const auto r = jellysim::testing::run_jellysim("experiment resonance --out " + dir.string() +
                                                 " --set resonance.multiples=[] --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("resonance.multiples"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}
