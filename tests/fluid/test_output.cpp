// PNG pictures of fluid fields (the VTK files are tested in tests/io/test_vtk.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid/tracers.hpp"
#include "jellysim/render/field_picture.hpp"

namespace jellysim {
namespace {

fluid::FlowState vortex_state(int n) {
  fluid::FlowState s(fluid::MacGrid(n, n, 2.0, 2.0));
  s.velocity = fluid::TaylorGreen{2.0, 1.0, 0.0}.sample(s.grid, 0.0);
  fluid::apply_velocity_boundaries(s.velocity, fluid::Boundaries::all(fluid::BoundaryType::free_slip));
  return s;
}

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

}  // namespace
}  // namespace jellysim
