// Charts: axes in the unit that fits the data, so tick labels need no exponent in a corner.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "jellysim/render/image.hpp"
#include "jellysim/render/plot.hpp"

namespace jellysim::render {
namespace {

TEST(Plot, AxesShowTheUnitThatFitsTheData) {
  EXPECT_EQ(fitting_unit("m", 0.028).unit, "cm");  // a bell's travel
  EXPECT_EQ(fitting_unit("m", 0.028).per_si, 100.0);
  EXPECT_EQ(fitting_unit("m/s", 0.0335).unit, "cm/s");
  EXPECT_EQ(fitting_unit("m/s", 0.0005).unit, "mm/s");
  EXPECT_EQ(fitting_unit("m/s²", 0.5).unit, "m/s²");  // already fits
  EXPECT_EQ(fitting_unit("m", 2e-7).unit, "µm");
  EXPECT_EQ(fitting_unit("N", 0.003).unit, "mN");  // no centi- for other units
  EXPECT_EQ(fitting_unit("s", 0.02).unit, "ms");
  EXPECT_EQ(fitting_unit("", 0.001).unit, "");  // a pure number stays one
  EXPECT_EQ(fitting_unit("°", 0.05).unit, "°");
  EXPECT_EQ(fitting_unit("m", 0.0).per_si, 1.0);
}

TEST(Plot, WritesAChartWithTheLegendOutsideTheData) {
  ChartSpec c;
  c.title = "travel";
  c.x_label = "t";
  c.x_unit = "s";
  c.y_label = "position";
  c.y_unit = "m";
  c.series.push_back({"bell", {0.0, 1.0, 2.0}, {0.0, 0.01, 0.028}});
  const auto png = std::filesystem::temp_directory_path() / "jellysim_test_chart.png";
  write_chart_png(c, png);
  // The series' colour (0, 114, 178) appears in the plot area (its line; the area ends 79.5 % down
  // the picture with one series) and otherwise only in the legend's sample, below the x axis's
  // labels (the bottom 15 % of the picture).
  const RgbImage image = read_png(png);
  int in_plot = 0, below = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Rgb p = image.at(x, y);
      if (std::abs(p[0] - 0) + std::abs(p[1] - 114) + std::abs(p[2] - 178) > 30) continue;
      if (y < 0.8 * image.height) {
        ++in_plot;
      } else {
        ++below;
        EXPECT_GT(y, 0.85 * image.height) << "a sample of the legend between the plot area and its axis labels";
      }
    }
  EXPECT_GT(in_plot, 100);
  EXPECT_GT(below, 5);
  std::filesystem::remove(png);
}

}  // namespace
}  // namespace jellysim::render
