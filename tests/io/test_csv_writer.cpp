// io::CsvWriter through io::OutputDir: shortest round-trip numbers, atomic files, quoted text cells.
#include "jellysim/io/output.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

TEST(Output, WritesAtomicallyAndFormatsShortestRoundTrip) {
  const auto dir = std::filesystem::temp_directory_path() / "jellysim_output_test";
  std::filesystem::remove_all(dir);
  const jellysim::io::OutputDir out(dir / "nested");
  jellysim::io::CsvWriter csv({"a", "b"});
  csv.row({0.1, 1e-300});
  csv.row({2.0, -3.5});
  out.write_text("x.csv", csv.text());
  std::ifstream in(dir / "nested" / "x.csv");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "a,b\n0.1,1e-300\n2,-3.5\n");
  for (const auto& entry : std::filesystem::directory_iterator(dir / "nested")) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos);  // no temporaries left
  }
  EXPECT_THROW(csv.row({1.0}), std::logic_error);
  std::filesystem::remove_all(dir);
}

// Text rows (batch.csv's): cells as given, quoted only where a comma, quote or line break needs it.
TEST(Output, TextRowsQuoteOnlyTheCellsThatNeedIt) {
  jellysim::io::CsvWriter csv({"run", "cells", "name", "failed"});
  csv.text_row({"0", "[24, 32]", "say \"hi\"", "false"});
  csv.text_row({"1", "", "plain", "true"});
  EXPECT_EQ(csv.text(), "run,cells,name,failed\n0,\"[24, 32]\",\"say \"\"hi\"\"\",false\n1,,plain,true\n");
  EXPECT_EQ(csv.rows(), 2u);
  EXPECT_THROW(csv.text_row({"2"}), std::logic_error);
}
