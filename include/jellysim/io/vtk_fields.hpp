#pragma once
// VTK output of grid-fluid fields for ParaView: one XML ImageData file (.vti, ASCII) per frame with
// cell-centred arrays, tracer particles as XML PolyData (.vtp), and a .pvd collection that ties
// the frames into a time series. Writers take a stream or a path; writing atomically (temp file +
// rename) is the caller's job.
#include <array>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "jellysim/fluid/grid.hpp"

namespace jellysim::io {

/// Writes velocity (vector, m/s), speed (m/s), vorticity (1/s), pressure (Pa) and divergence (1/s)
/// at the cell centres of `state` as VTK XML ImageData. The velocity ghosts must be filled.
void write_flow_vti(std::ostream& out, const fluid::FlowState& state);
void write_flow_vti(const std::filesystem::path& path, const fluid::FlowState& state);

/// Writes points (z = 0) as VTK XML PolyData vertices.
void write_points_vtp(std::ostream& out, const std::vector<Vec2>& points_m);
void write_points_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m);

/// Writes points (z = 0) joined by line segments (e.g. the springs of a body) as VTK XML PolyData.
void write_lines_vtp(std::ostream& out, const std::vector<Vec2>& points_m, const std::vector<std::array<int, 2>>& lines);
void write_lines_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points_m,
                     const std::vector<std::array<int, 2>>& lines);

/// One dataset of a time series: simulated time and the file name relative to the .pvd file.
struct PvdEntry {
  double time_s = 0.0;
  std::string file;
  int part = 0;  ///< several files at the same time step (e.g. field and tracers)
};

/// Writes a ParaView collection (.pvd) listing the entries.
void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries);
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

}  // namespace jellysim::io
