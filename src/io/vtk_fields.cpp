#include "jellysim/io/vtk_fields.hpp"

#include "jellysim/fluid3d/fluid_solver_3d.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/errors.hpp"
#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/fluid/projection.hpp"

namespace jellysim::io {
namespace {

/// Uncompressed bytes per zlib block (VTK's default).
constexpr std::size_t kBlockBytes = 32768;

/// Collects the arrays of one file: each <DataArray> element refers by offset to its bytes in the
/// appended section, stored as VTK's compressed-data header (UInt64: block count, block size,
/// size of a partial last block or 0, compressed size of each block) followed by the blocks.
class AppendedArrays {
 public:
  /// The element for `count` values of `type` ("Float64", "Float32", "Int32", "Int64") at `data`.
  std::string element(const std::string& indent, const char* type, const std::string& name, int components,
                      const void* data, std::size_t bytes) {
    std::ostringstream e;
    e << indent << "<DataArray type=\"" << type << '"';
    if (!name.empty()) e << " Name=\"" << name << '"';
    if (components != 1) e << " NumberOfComponents=\"" << components << '"';
    e << " format=\"appended\" offset=\"" << blob_.size() << "\"/>\n";
    append_compressed(static_cast<const unsigned char*>(data), bytes);
    return e.str();
  }
  std::string element(const std::string& indent, const VtkArray& a) {
    if (a.integer) {
      std::vector<std::int32_t> v(a.values.begin(), a.values.end());
      return element(indent, "Int32", a.name, a.components, v.data(), v.size() * 4);
    }
    if (a.single) {
      std::vector<float> v(a.values.begin(), a.values.end());
      return element(indent, "Float32", a.name, a.components, v.data(), v.size() * 4);
    }
    return element(indent, "Float64", a.name, a.components, a.values.data(), a.values.size() * 8);
  }
  void write(std::ostream& out) const {
    out << "  <AppendedData encoding=\"raw\">\n   _";
    out.write(blob_.data(), static_cast<std::streamsize>(blob_.size()));
    out << "\n  </AppendedData>\n";
  }

 private:
  void append_compressed(const unsigned char* data, std::size_t bytes) {
    const std::size_t blocks = (bytes + kBlockBytes - 1) / kBlockBytes;
    std::vector<std::uint64_t> header{blocks, kBlockBytes, bytes % kBlockBytes};
    std::string body;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t size = std::min(kBlockBytes, bytes - b * kBlockBytes);
      uLongf packed = compressBound(static_cast<uLong>(size));
      std::string block(packed, '\0');
      if (compress2(reinterpret_cast<Bytef*>(block.data()), &packed, data + b * kBlockBytes, static_cast<uLong>(size),
                    Z_BEST_SPEED) != Z_OK)
        throw std::runtime_error("zlib could not compress a VTK array");
      header.push_back(packed);
      body.append(block.data(), packed);
    }
    blob_.append(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
    blob_ += body;
  }
  std::string blob_;
};

const char* kFileAttributes = " version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
                              "compressor=\"vtkZLibDataCompressor\"";

std::vector<double> cell_values(const fluid::Field& f) {
  std::vector<double> v;
  v.reserve(static_cast<std::size_t>(f.count_x()) * static_cast<std::size_t>(f.count_y()));
  for (int j = 0; j < f.count_y(); ++j)
    for (int i = 0; i < f.count_x(); ++i) v.push_back(f(i, j));
  return v;
}

/// Writes what `write(stream)` produces to `path` through io::write_file, which reports the
/// reason of the call that failed (a stream keeps none).
template <class Write>
void write_to_path(const std::filesystem::path& path, Write&& write) {
  std::ostringstream out;
  write(out);
  write_file(path, out.view());
}

/// Full double precision on the stream for the duration of one write.
class PrecisionGuard {
 public:
  explicit PrecisionGuard(std::ostream& out)
      : out_(out), old_(out.precision(std::numeric_limits<double>::max_digits10)) {}
  ~PrecisionGuard() { out_.precision(old_); }
  PrecisionGuard(const PrecisionGuard&) = delete;
  PrecisionGuard& operator=(const PrecisionGuard&) = delete;

 private:
  std::ostream& out_;
  std::streamsize old_;
};

void check_sizes(const std::vector<VtkArray>& arrays, std::size_t tuples, const char* what) {
  for (const VtkArray& a : arrays)
    if (a.components < 1 || a.values.size() != tuples * static_cast<std::size_t>(a.components))
      throw std::invalid_argument("VTK array '" + a.name + "' has " + std::to_string(a.values.size()) +
                                  " values for " + std::to_string(tuples) + " " + what + " of " +
                                  std::to_string(a.components) + " components");
}

}  // namespace

void write_flow_vti(std::ostream& out, const fluid::FlowState& state) {
  const PrecisionGuard precision(out);
  const fluid::MacGrid& g = state.grid;
  const fluid::Velocity& vel = state.velocity;
  std::vector<double> velocity;
  velocity.reserve(3 * static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny));
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 c = fluid::velocity_at_centre(vel, i, j);
      velocity.insert(velocity.end(), {c.x, c.y, 0.0});
    }
  AppendedArrays arrays;
  const std::string in = "        ";
  // Single precision: a picture's and ParaView's needs, at half the bytes (issue 34).
  std::string cells = arrays.element(in, {"velocity", 3, std::move(velocity), false, true});
  cells += arrays.element(in, {"speed", 1, cell_values(fluid::speed_at_centres(vel)), false, true});
  cells += arrays.element(in, {"vorticity", 1, cell_values(fluid::vorticity_at_centres(vel)), false, true});
  cells += arrays.element(in, {"pressure", 1, cell_values(state.pressure), false, true});
  cells += arrays.element(in, {"divergence", 1, cell_values(fluid::divergence(vel)), false, true});
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\"" << kFileAttributes << ">\n"
      << "  <ImageData WholeExtent=\"0 " << g.nx << " 0 " << g.ny << " 0 0\" Origin=\"" << g.origin_m.x << ' '
      << g.origin_m.y << " 0\" Spacing=\"" << g.dx() << ' ' << g.dy() << " 1\">\n"
      << "    <Piece Extent=\"0 " << g.nx << " 0 " << g.ny << " 0 0\">\n"
      << "      <CellData Scalars=\"speed\" Vectors=\"velocity\">\n"
      << cells << "      </CellData>\n    </Piece>\n  </ImageData>\n";
  arrays.write(out);
  out << "</VTKFile>\n";
}

void write_flow_vti(const std::filesystem::path& path, const fluid::FlowState& state) {
  write_to_path(path, [&](std::ostream& out) { write_flow_vti(out, state); });
}

namespace {

/// The velocity at the centres of the 3D grid's cells (x fastest): each component the mean of the
/// cell's two faces along its axis.
std::vector<std::array<double, 3>> centre_velocities_3d(const fluid3d::FlowState3d& s) {
  const fluid3d::Grid3d& g = s.grid;
  std::vector<std::array<double, 3>> v;
  v.reserve(g.cell_count());
  fluid3d::for_each_interior_cell(g, [&](std::size_t I, int, int, int) {
    std::array<double, 3> c{};
    for (int d = 0; d < 3; ++d) c[d] = 0.5 * (s.velocity.c[d][I] + s.velocity.c[d][I + g.stride(d)]);
    v.push_back(c);
  });
  return v;
}

/// ∂(component c)/∂(axis d) at cell (i, j, k) from the centre velocities: central, one-sided at
/// the first and last cell along d.
double centre_derivative_3d(const fluid3d::Grid3d& g, const std::vector<std::array<double, 3>>& v, int c, int d,
                            fluid3d::Index3 at) {
  const auto flat = [&](fluid3d::Index3 p) {
    return static_cast<std::size_t>(p[0]) +
           static_cast<std::size_t>(g.n(0)) * (static_cast<std::size_t>(p[1]) + static_cast<std::size_t>(g.n(1)) * static_cast<std::size_t>(p[2]));
  };
  fluid3d::Index3 lo = at, hi = at;
  lo[d] = std::max(at[d] - 1, 0);
  hi[d] = std::min(at[d] + 1, g.n(d) - 1);
  return (v[flat(hi)][c] - v[flat(lo)][c]) / ((hi[d] - lo[d]) * g.h(d));
}

}  // namespace

void write_flow_vti(std::ostream& out, const fluid3d::FlowState3d& state) {
  const PrecisionGuard precision(out);
  const fluid3d::Grid3d& g = state.grid;
  const std::vector<std::array<double, 3>> centre = centre_velocities_3d(state);
  std::vector<double> velocity, speed, vorticity, pressure, divergence;
  for (const auto& c : centre) {
    velocity.insert(velocity.end(), c.begin(), c.end());
    speed.push_back(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
  }
  fluid3d::for_each_interior_cell(g, [&](std::size_t I, int i, int j, int k) {
    const auto d = [&](int c, int axis) { return centre_derivative_3d(g, centre, c, axis, {i, j, k}); };
    vorticity.insert(vorticity.end(), {d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1)});
    pressure.push_back(state.pressure[I]);
    divergence.push_back(fluid3d::divergence_at(g, state.velocity, i, j, k));
  });
  AppendedArrays arrays;
  const std::string in = "        ";
  std::string cells = arrays.element(in, {"velocity", 3, std::move(velocity), false, true});
  cells += arrays.element(in, {"speed", 1, std::move(speed), false, true});
  cells += arrays.element(in, {"vorticity", 3, std::move(vorticity), false, true});
  cells += arrays.element(in, {"pressure", 1, std::move(pressure), false, true});
  cells += arrays.element(in, {"divergence", 1, std::move(divergence), false, true});
  const auto& o = g.origin();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\"" << kFileAttributes << ">\n"
      << "  <ImageData WholeExtent=\"0 " << g.n(0) << " 0 " << g.n(1) << " 0 " << g.n(2) << "\" Origin=\"" << o[0]
      << ' ' << o[1] << ' ' << o[2] << "\" Spacing=\"" << g.h(0) << ' ' << g.h(1) << ' ' << g.h(2) << "\">\n"
      << "    <Piece Extent=\"0 " << g.n(0) << " 0 " << g.n(1) << " 0 " << g.n(2) << "\">\n"
      << "      <CellData Scalars=\"speed\" Vectors=\"velocity\">\n"
      << cells << "      </CellData>\n    </Piece>\n  </ImageData>\n";
  arrays.write(out);
  out << "</VTKFile>\n";
}

void write_flow_vti(const std::filesystem::path& path, const fluid3d::FlowState3d& state) {
  write_to_path(path, [&](std::ostream& out) { write_flow_vti(out, state); });
}

void write_polydata_vtp(std::ostream& out, const VtkPolyData& d) {
  const std::size_t n = d.points_m.size();
  const bool lines = !d.lines.empty();
  const std::size_t cells = lines ? d.lines.size() : n;
  check_sizes(d.point_data, n, "points");
  check_sizes(d.cell_data, cells, "cells");
  for (const auto& l : d.lines)
    for (int p : l)
      if (p < 0 || static_cast<std::size_t>(p) >= n)
        throw std::invalid_argument("VTK line refers to point " + std::to_string(p) + " of " + std::to_string(n));
  AppendedArrays arrays;
  const std::string in = "        ";
  std::vector<double> xyz;
  xyz.reserve(3 * n);
  for (Vec2 p : d.points_m) xyz.insert(xyz.end(), {p.x, p.y, 0.0});
  const std::string points = arrays.element(in, "Float64", "", 3, xyz.data(), xyz.size() * 8);
  std::vector<std::int64_t> connectivity, offsets;
  if (lines) {
    for (const auto& l : d.lines) connectivity.insert(connectivity.end(), {l[0], l[1]});
  } else {
    for (std::size_t k = 0; k < n; ++k) connectivity.push_back(static_cast<std::int64_t>(k));
  }
  const std::int64_t per_cell = lines ? 2 : 1;
  for (std::size_t k = 1; k <= cells; ++k) offsets.push_back(per_cell * static_cast<std::int64_t>(k));
  std::string topology = arrays.element(in, "Int64", "connectivity", 1, connectivity.data(), connectivity.size() * 8);
  topology += arrays.element(in, "Int64", "offsets", 1, offsets.data(), offsets.size() * 8);
  std::string point_data, cell_data;
  for (const VtkArray& a : d.point_data) point_data += arrays.element(in, a);
  for (const VtkArray& a : d.cell_data) cell_data += arrays.element(in, a);
  const char* cell_kind = lines ? "Lines" : "Verts";
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\"" << kFileAttributes << ">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << (lines ? 0 : n) << "\" NumberOfLines=\""
      << (lines ? cells : 0) << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <PointData>\n" << point_data << "      </PointData>\n"
      << "      <CellData>\n" << cell_data << "      </CellData>\n"
      << "      <Points>\n" << points << "      </Points>\n"
      << "      <" << cell_kind << ">\n" << topology << "      </" << cell_kind << ">\n"
      << "    </Piece>\n  </PolyData>\n";
  arrays.write(out);
  out << "</VTKFile>\n";
}

namespace {

/// Cells as VTK's connectivity and offsets arrays (a point outside [0, points) is refused).
struct CellArrays {
  std::vector<std::int64_t> connectivity, offsets;
  void add(std::span<const int> cell, std::size_t points) {
    for (int p : cell) {
      if (p < 0 || static_cast<std::size_t>(p) >= points)
        throw std::invalid_argument("VTK cell refers to point " + std::to_string(p) + " of " + std::to_string(points));
      connectivity.push_back(p);
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  std::string elements(AppendedArrays& arrays, const std::string& in) const {
    return arrays.element(in, "Int64", "connectivity", 1, connectivity.data(), connectivity.size() * 8) +
           arrays.element(in, "Int64", "offsets", 1, offsets.data(), offsets.size() * 8);
  }
};

}  // namespace

void write_surface_vtp(std::ostream& out, const VtkSurface3d& s) {
  const std::size_t n = s.points_m.size();
  check_sizes(s.point_data, n, "points");
  CellArrays polys, lines;
  for (const auto& t : s.triangles) polys.add(t, n);
  for (const auto& l : s.polylines) {
    if (l.size() < 2) throw std::invalid_argument("VTK polyline of " + std::to_string(l.size()) + " point(s)");
    lines.add(l, n);
  }
  AppendedArrays arrays;
  const std::string in = "        ";
  std::vector<double> xyz;
  xyz.reserve(3 * n);
  for (const fluid3d::Vec3& p : s.points_m) xyz.insert(xyz.end(), p.begin(), p.end());
  const std::string points = arrays.element(in, "Float64", "", 3, xyz.data(), xyz.size() * 8);
  std::string point_data;
  for (const VtkArray& a : s.point_data) point_data += arrays.element(in, a);
  const std::string poly_cells = polys.elements(arrays, in), line_cells = lines.elements(arrays, in);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\"" << kFileAttributes << ">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << s.polylines.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"" << s.triangles.size() << "\">\n"
      << "      <PointData>\n" << point_data << "      </PointData>\n"
      << "      <Points>\n" << points << "      </Points>\n"
      << "      <Lines>\n" << line_cells << "      </Lines>\n"
      << "      <Polys>\n" << poly_cells << "      </Polys>\n"
      << "    </Piece>\n  </PolyData>\n";
  arrays.write(out);
  out << "</VTKFile>\n";
}

void write_polydata_vtp(const std::filesystem::path& path, const VtkPolyData& data) {
  write_to_path(path, [&](std::ostream& out) { write_polydata_vtp(out, data); });
}

void write_points_vtp(std::ostream& out, const std::vector<Vec2>& points_m) {
  VtkPolyData d;
  d.points_m = points_m;
  VtkArray id{"id", 1, {}, true};
  for (std::size_t k = 0; k < points_m.size(); ++k) id.values.push_back(static_cast<double>(k));
  d.point_data.push_back(std::move(id));
  write_polydata_vtp(out, d);
}

void write_points_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m) {
  write_to_path(path, [&](std::ostream& out) { write_points_vtp(out, points_m); });
}

void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries) {
  const PrecisionGuard precision(out);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const PvdEntry& e : entries) {
    out << "    <DataSet timestep=\"" << e.time_s << "\" group=\"\" part=\"" << e.part << '"';
    if (!e.name.empty()) out << " name=\"" << e.name << '"';
    out << " file=\"" << e.file << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries) {
  write_to_path(path, [&](std::ostream& out) { write_pvd(out, entries); });
}

}  // namespace jellysim::io
