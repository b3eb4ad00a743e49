// VTK output for ParaView: binary appended arrays, zlib-compressed, that decode to exactly the
// values written; named point and cell data; named parts in the .pvd collection.
#include <gtest/gtest.h>

#include <cerrno>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../flow_fixtures.hpp"
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"
#include "jellysim/io/vtk_fields.hpp"

namespace jellysim::io {
namespace {

using testing::vortex_state;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

/// Decodes array `name` of a file as ParaView does: its offset into the appended section, VTK's
/// compressed-data header (block count, block size, partial last block, compressed sizes), the
/// zlib blocks. An empty name finds the first array without one (the points); `from`: the first
/// such array after that position.
template <class T>
std::vector<T> read_array(const std::string& file, const std::string& name, std::size_t from = 0) {
  const std::size_t element = name.empty() ? file.find("<Points>", from) : file.find("Name=\"" + name + "\"", from);
  if (element == std::string::npos) throw std::runtime_error("no array " + name);
  const std::size_t offset = std::stoull(file.substr(file.find("offset=\"", element) + 8));
  const std::size_t base = file.find('_', file.find("<AppendedData encoding=\"raw\">")) + 1;
  const char* p = file.data() + base + offset;
  std::uint64_t header[3];
  std::memcpy(header, p, sizeof header);
  std::vector<std::uint64_t> packed(header[0]);
  std::memcpy(packed.data(), p + sizeof header, 8 * header[0]);
  const char* block = p + sizeof header + 8 * header[0];
  std::string raw;
  for (std::uint64_t b = 0; b < header[0]; ++b) {
    uLongf size = b + 1 == header[0] && header[2] != 0 ? header[2] : header[1];
    std::string out(size, '\0');
    if (uncompress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(block), packed[b]) != Z_OK)
      throw std::runtime_error("bad zlib block in " + name);
    raw.append(out.data(), size);
    block += packed[b];
  }
  std::vector<T> values(raw.size() / sizeof(T));
  std::memcpy(values.data(), raw.data(), raw.size());
  return values;
}

TEST(VtkOutput, ImageDataArraysDecodeToTheCellValues) {
  const fluid::FlowState s = vortex_state(6);
  std::ostringstream out;
  write_flow_vti(out, s);
  const std::string text = out.str();
  EXPECT_NE(text.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(text.find("WholeExtent=\"0 6 0 6 0 0\""), std::string::npos);
  EXPECT_NE(text.find("Spacing=\"0.33333333333333331 0.33333333333333331 1\""), std::string::npos);
  EXPECT_EQ(count(text, "<DataArray"), 5u);
  // The flow's fields are Float32: the values rounded to single precision.
  EXPECT_EQ(count(text, "type=\"Float32\""), 5u);
  const fluid::Field speed = fluid::speed_at_centres(s.velocity);
  const std::vector<float> read = read_array<float>(text, "speed");
  ASSERT_EQ(read.size(), 36u);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) EXPECT_EQ(read[static_cast<std::size_t>(6 * j + i)], static_cast<float>(speed(i, j)));
  const std::vector<float> velocity = read_array<float>(text, "velocity");
  ASSERT_EQ(velocity.size(), 108u);
  const Vec2 c = fluid::velocity_at_centre(s.velocity, 2, 3);
  EXPECT_EQ(velocity[3 * (6 * 3 + 2)], static_cast<float>(c.x));
  EXPECT_EQ(velocity[3 * (6 * 3 + 2) + 1], static_cast<float>(c.y));
  EXPECT_EQ(velocity[3 * (6 * 3 + 2) + 2], 0.0f);
}

TEST(VtkOutput, LargeArraysSpanSeveralCompressedBlocks) {
  const fluid::FlowState s = vortex_state(80);  // 6400 cells x 3 x 4 bytes: 3 blocks of 32 KiB
  std::ostringstream out;
  write_flow_vti(out, s);
  const std::vector<float> velocity = read_array<float>(out.str(), "velocity");
  ASSERT_EQ(velocity.size(), 3u * 6400u);
  const Vec2 c = fluid::velocity_at_centre(s.velocity, 79, 79);
  EXPECT_EQ(velocity[3 * 6399], static_cast<float>(c.x));
  EXPECT_LT(out.str().size(), 4u * 6400u * 7u);  // smaller than the raw floats
}

TEST(VtkOutput, PolyDataCarriesNamedPointAndCellData) {
  VtkPolyData d;
  d.points_m = {{0.1, 0.2}, {0.3, 0.4}, {0.5, 0.7}};
  d.lines = {{0, 1}, {1, 2}};
  d.point_data.push_back({"kind", 1, {0, 0, 2}, true});
  d.point_data.push_back({"velocity", 3, {1, 2, 0, 3, 4, 0, 5, 6, 0}, false});
  d.cell_data.push_back({"muscle", 1, {0, 1}, true});
  std::ostringstream out;
  write_polydata_vtp(out, d);
  const std::string text = out.str();
  EXPECT_NE(text.find("NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"2\""), std::string::npos);
  EXPECT_EQ(read_array<double>(text, ""), (std::vector<double>{0.1, 0.2, 0, 0.3, 0.4, 0, 0.5, 0.7, 0}));
  EXPECT_EQ(read_array<std::int64_t>(text, "connectivity"), (std::vector<std::int64_t>{0, 1, 1, 2}));
  EXPECT_EQ(read_array<std::int64_t>(text, "offsets"), (std::vector<std::int64_t>{2, 4}));
  EXPECT_EQ(read_array<std::int32_t>(text, "kind"), (std::vector<std::int32_t>{0, 0, 2}));
  EXPECT_EQ(read_array<double>(text, "velocity")[4], 4.0);
  EXPECT_EQ(read_array<std::int32_t>(text, "muscle"), (std::vector<std::int32_t>{0, 1}));
  d.cell_data.front().values.pop_back();
  EXPECT_THROW(write_polydata_vtp(out, d), std::invalid_argument);  // one value short
}

// The 3D swimmer's markers (issue 40): a tetrahedron's two faces and a polyline hanging from it.
TEST(VtkOutput, SurfacePolyDataHasTrianglesLinesAndPointData) {
  VtkSurface3d d;
  d.points_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 0, -2}};
  d.triangles = {{0, 1, 2}, {0, 3, 1}};
  d.polylines = {{0, 4, 5}};
  d.point_data.push_back({"force", 3, std::vector<double>(18, 0.5)});
  std::ostringstream out;
  write_surface_vtp(out, d);
  const std::string text = out.str();
  EXPECT_NE(text.find("NumberOfPoints=\"6\" NumberOfVerts=\"0\" NumberOfLines=\"1\" NumberOfStrips=\"0\" "
                      "NumberOfPolys=\"2\""),
            std::string::npos);
  EXPECT_EQ(read_array<double>(text, "")[11], 1.0);  // the fourth point's z
  // The cells' connectivity and offsets: the lines' first (VTK's order of sections), then the polygons'.
  const std::size_t polys = text.find("<Polys>");
  EXPECT_EQ(read_array<std::int64_t>(text, "connectivity"), (std::vector<std::int64_t>{0, 4, 5}));
  EXPECT_EQ(read_array<std::int64_t>(text, "offsets"), (std::vector<std::int64_t>{3}));
  EXPECT_EQ(read_array<std::int64_t>(text, "connectivity", polys), (std::vector<std::int64_t>{0, 1, 2, 0, 3, 1}));
  EXPECT_EQ(read_array<std::int64_t>(text, "offsets", polys), (std::vector<std::int64_t>{3, 6}));
  EXPECT_EQ(read_array<double>(text, "force").size(), 18u);
  d.triangles.push_back({0, 1, 6});
  EXPECT_THROW(write_surface_vtp(out, d), std::invalid_argument);  // no point 6
  d.triangles.pop_back();
  d.polylines.push_back({2});
  EXPECT_THROW(write_surface_vtp(out, d), std::invalid_argument);  // a line of one point
}

TEST(VtkOutput, TimeSeriesListsEveryFrameWithNamedParts) {
  std::ostringstream out;
  write_pvd(out, {{0.0, "flow_0000.vti", 0, "field"}, {0.5, "flow_0001.vti", 0, "field"},
                  {0.5, "tracers_0001.vtp", 1, "tracers"}});
  EXPECT_EQ(count(out.str(), "<DataSet"), 3u);
  EXPECT_NE(out.str().find("timestep=\"0.5\" group=\"\" part=\"1\" name=\"tracers\" file=\"tracers_0001.vtp\""),
            std::string::npos);
}

// The 3D flow's .vti (issue 40): a solid-body rotation about z with a uniform axial speed, u =
// (−ω(y − y0), ω(x − x0), W), is linear, so the centre averages, the central and one-sided
// differences are exact: vorticity (0, 0, 2ω) and divergence 0 in every cell, the velocity at the
// centres the field's, each to single precision; the extent, origin and spacing those of the grid.
TEST(VtkOutput, ThreeDimensionalImageDataHoldsTheCentreVelocityAndVorticity) {
  const fluid3d::Grid3d g({4, 3, 5}, {0.4, 0.6, 0.5}, {-0.2, 0.0, 0.1});
  fluid3d::FlowState3d s(g);
  const double omega = 1.5, w = 0.25, x0 = 0.05, y0 = 0.2;
  const auto field = [&](int c, const fluid3d::Vec3& p) {
    return c == 0 ? -omega * (p[1] - y0) : c == 1 ? omega * (p[0] - x0) : w;
  };
  for (int c = 0; c < 3; ++c)
    for (int k = -1; k <= g.n(2); ++k)
      for (int j = -1; j <= g.n(1); ++j)
        for (int i = -1; i <= g.n(0); ++i) s.velocity.c[c][g.index(i, j, k)] = field(c, g.position(c, i, j, k));
  fluid3d::for_each_interior_cell(g, [&](std::size_t I, int i, int, int) { s.pressure[I] = 10.0 * i; });
  std::ostringstream out;
  write_flow_vti(out, s);
  const std::string text = out.str();
  EXPECT_NE(text.find("WholeExtent=\"0 4 0 3 0 5\""), std::string::npos);
  EXPECT_NE(text.find("Origin=\"-0.20000000000000001 0 0.10000000000000001\""), std::string::npos);
  EXPECT_EQ(count(text, "type=\"Float32\""), 5u);
  const auto velocity = read_array<float>(text, "velocity"), vorticity = read_array<float>(text, "vorticity");
  const auto divergence = read_array<float>(text, "divergence"), pressure = read_array<float>(text, "pressure");
  ASSERT_EQ(velocity.size(), 3 * g.cell_count());
  ASSERT_EQ(vorticity.size(), 3 * g.cell_count());
  std::size_t n = 0;
  fluid3d::for_each_interior_cell(g, [&](std::size_t, int i, int j, int k) {
    const fluid3d::Vec3 p = g.position(3, i, j, k);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(velocity[3 * n + c], field(c, p), 1e-7) << n;
    EXPECT_NEAR(vorticity[3 * n], 0.0, 1e-6);
    EXPECT_NEAR(vorticity[3 * n + 1], 0.0, 1e-6);
    EXPECT_NEAR(vorticity[3 * n + 2], 2.0 * omega, 1e-6);
    EXPECT_NEAR(divergence[n], 0.0, 1e-6);
    EXPECT_EQ(pressure[n], static_cast<float>(10.0 * i));
    ++n;
  });
}

TEST(VtkOutput, PointsGetTheirIndexAsId) {
  const auto path = std::filesystem::temp_directory_path() / "jellysim_test_points.vtp";
  write_points_vtp(path, {{0.1, 0.2}, {0.3, 0.4}});
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("NumberOfPoints=\"2\" NumberOfVerts=\"2\""), std::string::npos);
  EXPECT_EQ(read_array<std::int32_t>(text, "id"), (std::vector<std::int32_t>{0, 1}));
  std::filesystem::remove(path);
}

TEST(Vtk, AFullDiskIsReportedWithThePathAndTheReason) {
  // /dev/full fails every write with ENOSPC, as a full disk does.
  const fluid::FlowState s(fluid::MacGrid(8, 8, 1.0, 1.0));
  try {
    write_flow_vti(std::filesystem::path("/dev/full"), s);
    FAIL() << "writing to /dev/full succeeded";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("'/dev/full'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(os_reason(ENOSPC)), std::string::npos) << e.what();
  }
}

// A file larger than the stream's buffer: the write that fails is inside the data, not the last
// flush, and its reason (ENOSPC) is the one reported (issue 35, item 12: "Input/output error").
TEST(Vtk, AFullDiskDuringALargeFileIsReportedAsNoSpace) {
  VtkPolyData d;
  std::uint64_t x = 88172645463325252ull;  // xorshift: values zlib cannot shrink
  for (int k = 0; k < 20000; ++k) {
    x ^= x << 13; x ^= x >> 7; x ^= x << 17;
    d.points_m.push_back({static_cast<double>(x % 1000003) * 1e-6, static_cast<double>(x % 999983) * 1e-6});
  }
  try {
    write_polydata_vtp(std::filesystem::path("/dev/full"), d);
    FAIL() << "writing to /dev/full succeeded";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find(os_reason(ENOSPC)), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace jellysim::io
