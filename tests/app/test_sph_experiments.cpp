// The particle-fluid experiments on the command line: short runs write their files and the
// summary keys of issue 6; bad input exits 2 naming the field; same inputs give identical files.
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "../cli_runner.hpp"

namespace cli = jellysim::testing;

namespace fs = std::filesystem;

namespace {

using Result = cli::CliResult;

Result jellysim(const std::string& args) { return cli::run_jellysim(args + " --quiet"); }
std::string read_file(const fs::path& p) { return cli::read_text_file(p); }
fs::path scratch(const std::string& name) { return cli::fresh_scratch_dir("sph_" + name); }

TEST(SphExperiments, MosquitoLarvaWritesTheSummaryKeysOfTheIssue) {
  const fs::path out = scratch("larva");
  const Result r = jellysim("experiment mosquito-larva --out " + out.string() + " --duration 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  for (const char* key : {"simulated_seconds", "wall_seconds", "steps", "rejected_steps", "function_evaluations"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_DOUBLE_EQ(summary["simulated_seconds"].get<double>(), 0.2);
  EXPECT_EQ(summary["fluid_particles"], 625);
  EXPECT_TRUE(fs::exists(out / "frames.csv"));
  EXPECT_TRUE(fs::exists(out / "mosquito_larva.png"));
  fs::remove_all(out);
}

TEST(SphExperiments, SameInputsGiveIdenticalFrames) {
  const fs::path a = scratch("stream_a"), b = scratch("stream_b");
  ASSERT_EQ(jellysim("experiment sph-stream --out " + a.string() + " --duration 1").exit_code, 0);
  ASSERT_EQ(jellysim("experiment sph-stream --out " + b.string() + " --duration 1").exit_code, 0);
  EXPECT_EQ(read_file(a / "frames.csv"), read_file(b / "frames.csv"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(SphExperiments, BadInputExitsTwoNamingTheFieldAndWritesNothing) {
  const fs::path out = scratch("bad");
  for (const std::string set : {"fluid.gas_constant=-1", "larva.contraction=2", "run.threads=-1",
                                "fluid.particles=0"}) {
    const Result r = jellysim("experiment mosquito-larva --out " + out.string() + " --set " + set);
    EXPECT_EQ(r.exit_code, 2) << set;
    EXPECT_NE(r.output.find(set.substr(0, set.find('='))), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
}

}  // namespace
