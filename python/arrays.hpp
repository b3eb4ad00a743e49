#pragma once
// NumPy arrays from the library's containers (docs/python.md): copies of point lists and meshes,
// read-only views of the solver's grid fields that keep their owner alive.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "jellysim/fluid/grid.hpp"
#include "jellysim/geometry/mesh.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::python {

namespace py = pybind11;

/// (N, 2) float64 copy of the points.
py::array_t<double> points_array(const std::vector<Vec2>& points);
/// (N, 3) float64 copy of the mesh's vertex positions.
py::array_t<double> vertices_array(const geometry::Mesh& mesh);
/// (T, 3) int64 copy of the mesh's triangles (vertex indices).
py::array_t<std::int64_t> triangles_array(const geometry::Mesh& mesh);
/// 1D float64 copy.
py::array_t<double> vector_array(const std::vector<double>& values);

/// The field's interior samples as a read-only (count_y, count_x) view indexed [j, i] (row j along
/// y), strided over the ghost layer; `owner` (the Python object owning the storage) stays alive
/// while the view does.
py::array field_view(const fluid::Field& field, py::handle owner);
/// x (along = 0) or y (along = 1) coordinates of the field's interior samples (m).
py::array_t<double> sample_coordinates(const fluid::Field& field, int along);

}  // namespace jellysim::python
