// PNG pictures of fluid fields (the VTK files are tested in tests/io/test_vtk.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../flow_fixtures.hpp"
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid/tracers.hpp"
#include "jellysim/render/field_picture.hpp"

namespace jellysim {
namespace {

using testing::vortex_state;

TEST(FieldPicture, WritesAPngFile) {
  const fluid::FlowState s = vortex_state(16);
  const auto tracers = fluid::Tracers::lattice({0.1, 0.1}, {1.9, 1.9}, 8, 8);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "jellysim_test_fluid_png";
  std::filesystem::create_directories(dir);
  const std::filesystem::path png = dir / "vortex.png";
  std::filesystem::remove(png);
  render::FieldPictureOptions options;
  options.quantity = render::FieldQuantity::vorticity;
  options.panel_px = 200;
  render::FieldPicture first, second;
  first.state = second.state = &s;
  first.caption = "vortex";
  first.tracers_m = tracers.positions();
  second.caption = "again";
  render::write_field_panels_png({first, second}, 2, options, png);
  ASSERT_TRUE(std::filesystem::exists(png));
  std::ifstream in(png, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

// One picture by our own rasteriser: the field's colours where the flow is, the segments in ink,
// the tracers in magenta, inside a square picture of the asked size.
TEST(FieldPicture, DrawsFieldSegmentsAndTracers) {
  const fluid::FlowState s = vortex_state(16);
  render::FieldPicture p;
  p.state = &s;
  p.caption = "vortex";
  p.tracers_m = {{0.5, 0.5}};
  p.segments_m = {{Vec2{0.2, 1.5}, Vec2{1.8, 1.5}}};
  render::FieldPictureOptions options;
  options.quantity = render::FieldQuantity::vorticity;
  options.arrows = false;
  options.panel_px = 400;
  const render::RgbImage image = render::draw_field_picture(p, options);
  ASSERT_EQ(image.width, 400);
  ASSERT_EQ(image.height, 400);
  int ink = 0, magenta = 0, red = 0, blue = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const auto c = image.at(x, y);
      ink += c[0] < 40 && c[1] < 40 && c[2] < 40 ? 1 : 0;
      magenta += c[0] > 200 && c[1] < 80 && c[2] > 120 ? 1 : 0;
      red += c[0] > 150 && c[1] < 60 && c[2] < 60 ? 1 : 0;  // positive vorticity
      blue += c[2] > 150 && c[0] < 80 ? 1 : 0;              // negative vorticity
    }
  EXPECT_GT(ink, 300);  // frame, ticks, text and the 2.5 px segment across the plot
  EXPECT_GT(magenta, 3);
  EXPECT_GT(red, 1000);  // a Taylor-Green vortex array: both signs over large areas
  EXPECT_GT(blue, 1000);
}

}  // namespace
}  // namespace jellysim
