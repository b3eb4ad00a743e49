// NumPy arrays from the library's containers (arrays.hpp).
#include "arrays.hpp"

namespace jellysim::python {

namespace {

/// A (rows, columns) float64 array filled by get(row, column).
template <typename T, typename Get>
py::array_t<T> table(std::size_t rows, std::size_t columns, Get get) {
  py::array_t<T> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
  auto m = a.template mutable_unchecked<2>();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < columns; ++c) m(static_cast<py::ssize_t>(r), static_cast<py::ssize_t>(c)) = get(r, c);
  return a;
}

}  // namespace

py::array_t<double> points_array(const std::vector<Vec2>& points) {
  return table<double>(points.size(), 2, [&](std::size_t r, std::size_t c) { return c == 0 ? points[r].x : points[r].y; });
}

py::array_t<double> vertices_array(const geometry::Mesh& mesh) {
  return table<double>(mesh.positions.size(), 3, [&](std::size_t r, std::size_t c) {
    const geometry::Vec3& p = mesh.positions[r];
    return c == 0 ? p.x : c == 1 ? p.y : p.z;
  });
}

py::array_t<std::int64_t> triangles_array(const geometry::Mesh& mesh) {
  return table<std::int64_t>(mesh.triangle_count(), 3, [&](std::size_t r, std::size_t c) {
    return static_cast<std::int64_t>(mesh.indices[3 * r + c]);
  });
}

py::array_t<double> vector_array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

py::array field_view(const fluid::Field& field, py::handle owner) {
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  py::array view(py::dtype::of<double>(), {field.count_y(), field.count_x()},
                 {static_cast<py::ssize_t>(field.stride()) * item, item}, field.ptr(0, 0), owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

py::array_t<double> sample_coordinates(const fluid::Field& field, int along) {
  const int count = along == 0 ? field.count_x() : field.count_y();
  py::array_t<double> a(count);
  auto m = a.mutable_unchecked<1>();
  for (int k = 0; k < count; ++k) m(k) = along == 0 ? field.position(k, 0).x : field.position(0, k).y;
  return a;
}

}  // namespace jellysim::python
