#include "jellysim/io/vtk_fields.hpp"

#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/projection.hpp"

namespace jellysim::io {
namespace {

void write_cell_array(std::ostream& out, const char* name, const fluid::Field& f) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (int j = 0; j < f.count_y(); ++j) {
    out << "         ";
    for (int i = 0; i < f.count_x(); ++i) out << ' ' << f(i, j);
    out << '\n';
  }
  out << "        </DataArray>\n";
}

std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open " + path.string() + " for writing");
  return out;
}

void check_written(std::ostream& out, const std::filesystem::path& path) {
  out.flush();
  if (!out) throw std::runtime_error("failed writing " + path.string());
}

// Full double precision on the stream for the duration of one write.
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

}  // namespace

void write_flow_vti(std::ostream& out, const fluid::FlowState& state) {
  const PrecisionGuard precision(out);
  const fluid::MacGrid& g = state.grid;
  const fluid::Velocity& vel = state.velocity;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      << "  <ImageData WholeExtent=\"0 " << g.nx << " 0 " << g.ny << " 0 0\" Origin=\"" << g.origin_m.x << ' '
      << g.origin_m.y << " 0\" Spacing=\"" << g.dx() << ' ' << g.dy() << " 1\">\n"
      << "    <Piece Extent=\"0 " << g.nx << " 0 " << g.ny << " 0 0\">\n"
      << "      <CellData Scalars=\"speed\" Vectors=\"velocity\">\n"
      << "        <DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int j = 0; j < g.ny; ++j) {
    out << "         ";
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 c = fluid::velocity_at_centre(vel, i, j);
      out << ' ' << c.x << ' ' << c.y << " 0";
    }
    out << '\n';
  }
  out << "        </DataArray>\n";
  write_cell_array(out, "speed", fluid::speed_at_centres(vel));
  write_cell_array(out, "vorticity", fluid::vorticity_at_centres(vel));
  write_cell_array(out, "pressure", state.pressure);
  write_cell_array(out, "divergence", fluid::divergence(vel));
  out << "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
}

void write_flow_vti(const std::filesystem::path& path, const fluid::FlowState& state) {
  std::ofstream out = open_for_writing(path);
  write_flow_vti(out, state);
  check_written(out, path);
}

void write_points_vtp(std::ostream& out, const std::vector<Vec2>& points_m) {
  const PrecisionGuard precision(out);
  const std::size_t n = points_m.size();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n
      << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec2& p : points_m) out << "          " << p.x << ' ' << p.y << " 0\n";
  out << "        </DataArray>\n      </Points>\n      <Verts>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (std::size_t k = 0; k < n; ++k) out << ' ' << k;
  out << "\n        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  for (std::size_t k = 1; k <= n; ++k) out << ' ' << k;
  out << "\n        </DataArray>\n      </Verts>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

void write_points_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m) {
  std::ofstream out = open_for_writing(path);
  write_points_vtp(out, points_m);
  check_written(out, path);
}

void write_lines_vtp(std::ostream& out, const std::vector<Vec2>& points_m, const std::vector<std::array<int, 2>>& lines) {
  const PrecisionGuard precision(out);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << points_m.size() << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << lines.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec2& p : points_m) out << "          " << p.x << ' ' << p.y << " 0\n";
  out << "        </DataArray>\n      </Points>\n      <Lines>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (const auto& l : lines) out << ' ' << l[0] << ' ' << l[1];
  out << "\n        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  for (std::size_t k = 1; k <= lines.size(); ++k) out << ' ' << 2 * k;
  out << "\n        </DataArray>\n      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

void write_lines_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m,
                     const std::vector<std::array<int, 2>>& lines) {
  std::ofstream out = open_for_writing(path);
  write_lines_vtp(out, points_m, lines);
  check_written(out, path);
}

void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries) {
  const PrecisionGuard precision(out);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const PvdEntry& e : entries)
    out << "    <DataSet timestep=\"" << e.time_s << "\" group=\"\" part=\"" << e.part << "\" file=\"" << e.file
        << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries) {
  std::ofstream out = open_for_writing(path);
  write_pvd(out, entries);
  check_written(out, path);
}

}  // namespace jellysim::io
