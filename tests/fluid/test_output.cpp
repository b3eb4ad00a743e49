// VTK and PNG output of fluid fields: well-formed files with the expected sizes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid/tracers.hpp"
#include "jellysim/io/vtk_fields.hpp"
#include "jellysim/render/field_picture.hpp"

namespace jellysim {
namespace {

fluid::FlowState vortex_state(int n) {
  fluid::FlowState s(fluid::MacGrid(n, n, 2.0, 2.0));
  s.velocity = fluid::TaylorGreen{2.0, 1.0, 0.0}.sample(s.grid, 0.0);
  fluid::apply_velocity_boundaries(s.velocity, fluid::Boundaries::all(fluid::BoundaryType::free_slip));
  return s;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

TEST(VtkOutput, ImageDataHasOneValuePerCellForEveryArray) {
  const fluid::FlowState s = vortex_state(6);
  std::ostringstream out;
  io::write_flow_vti(out, s);
  const std::string text = out.str();
  EXPECT_NE(text.find("WholeExtent=\"0 6 0 6 0 0\""), std::string::npos);
  EXPECT_NE(text.find("Spacing=\"0.33333333333333331 0.33333333333333331 1\""), std::string::npos);
  EXPECT_EQ(count(text, "<DataArray"), 5u);
  // The speed array holds 36 numbers.
  const std::size_t start = text.find(">", text.find("Name=\"speed\"")) + 1;
  std::istringstream values(text.substr(start, text.find("</DataArray>", start) - start));
  int n = 0;
  for (double v; values >> v;) ++n;
  EXPECT_EQ(n, 36);
}

TEST(VtkOutput, TimeSeriesListsEveryFrame) {
  std::ostringstream out;
  io::write_pvd(out, {{0.0, "flow_0000.vti", 0}, {0.5, "flow_0001.vti", 0}, {0.5, "tracers_0001.vtp", 1}});
  EXPECT_EQ(count(out.str(), "<DataSet"), 3u);
  EXPECT_NE(out.str().find("timestep=\"0.5\" group=\"\" part=\"1\" file=\"tracers_0001.vtp\""), std::string::npos);
  std::ostringstream points;
  io::write_points_vtp(points, {{0.1, 0.2}, {0.3, 0.4}});
  EXPECT_NE(points.str().find("NumberOfPoints=\"2\""), std::string::npos);
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
