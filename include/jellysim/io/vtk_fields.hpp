#pragma once
// VTK output for ParaView: grid-fluid fields as XML ImageData (.vti, cell-centred arrays), points
// and springs as XML PolyData (.vtp) with named point and cell data, and a .pvd collection that
// ties the frames into a time series with named parts (the flow's fields in single precision,
// the points' positions and data in double). Arrays are raw binary in the file's
// appended section, zlib-compressed (vtkZLibDataCompressor, 32 KiB blocks), so a frame takes a
// fraction of the ASCII file's space and time. Writers take a stream or a path (io::write_file:
// written in place, never through a symlink); into a results directory, write atomically
// through the stream (io::write_streamed).
#include <array>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "jellysim/fluid/grid.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::io {

/// One named data array: `components` values per point or cell, Float64, or Int32 when `integer`
/// (kinds, flags, ids), or Float32 when `single` (the flow's fields on the grid: half the bytes;
/// ParaView reads either).
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  ///< tuples × components
  bool integer = false;
  bool single = false;
};

/// Points in the slice plane (z = 0), each a vertex or joined by line segments, with data.
struct VtkPolyData {
  std::vector<Vec2> points_m;
  std::vector<std::array<int, 2>> lines;  ///< empty: every point is a vertex cell
  std::vector<VtkArray> point_data;
  std::vector<VtkArray> cell_data;        ///< one tuple per vertex (no lines) or per line
};

/// Writes velocity (vector, m/s), speed (m/s), vorticity (1/s), pressure (Pa) and divergence (1/s)
/// at the cell centres of `state` as VTK XML ImageData. The velocity ghosts must be filled.
void write_flow_vti(std::ostream& out, const fluid::FlowState& state);
void write_flow_vti(const std::filesystem::path& path, const fluid::FlowState& state);

/// The 3D flow (issue 40, docs/three-d.md) as VTK XML ImageData for ParaView: velocity (vector,
/// m/s, the two faces of each cell averaged), speed (m/s), vorticity (vector, 1/s: central
/// differences of the centre velocities, one-sided in the first and last cells), pressure (Pa) and
/// divergence (1/s, the MAC divergence) at the cell centres, Float32.
void write_flow_vti(std::ostream& out, const fluid3d::FlowState3d& state);
void write_flow_vti(const std::filesystem::path& path, const fluid3d::FlowState3d& state);

/// Writes the points, their cells and their data as VTK XML PolyData; throws std::invalid_argument
/// when an array's size does not match its points or cells.
void write_polydata_vtp(std::ostream& out, const VtkPolyData& data);
void write_polydata_vtp(const std::filesystem::path& path, const VtkPolyData& data);

/// A surface in 3D: triangles and polylines over one set of points, with point data (the 3D
/// swimmer's shell bell and its tentacles, issue 40).
struct VtkSurface3d {
  std::vector<fluid3d::Vec3> points_m;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<int>> polylines;  ///< each at least two points
  std::vector<VtkArray> point_data;
};

/// Writes the surface as VTK XML PolyData (Polys and Lines); throws std::invalid_argument when an
/// array's size does not match the points, or a cell names a point that is not there.
void write_surface_vtp(std::ostream& out, const VtkSurface3d& surface);

/// Points (z = 0) as vertices with an `id` array (their index).
void write_points_vtp(std::ostream& out, const std::vector<Vec2>& points_m);
void write_points_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m);

/// One dataset of a time series: simulated time, the file name relative to the .pvd file, and
/// which part of the time step it is (e.g. 0 field, 1 tracers), named for ParaView's pipeline.
struct PvdEntry {
  double time_s = 0.0;
  std::string file;
  int part = 0;
  std::string name;  ///< e.g. "field", "tracers", "body"
};

/// Writes a ParaView collection (.pvd) listing the entries.
void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries);
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

}  // namespace jellysim::io
