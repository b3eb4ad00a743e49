#include "jellysim/io/interchange.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::io {

using geometry::Vec3;

double ExportCamera::near_m() const {
  return frames.empty() ? 0.0 : near_fraction * geometry::norm(frames.front().target - frames.front().eye);
}

double ExportCamera::far_m() const {
  return frames.empty() ? 0.0 : far_fraction * geometry::norm(frames.front().target - frames.front().eye);
}

bool ExportCamera::still() const {
  const auto same = [&](const CameraFrame& f) {
    const CameraFrame& a = frames.front();
    return f.eye == a.eye && f.target == a.target && f.up == a.up;
  };
  return frames.empty() || std::all_of(frames.begin(), frames.end(), same);
}

std::array<Vec3, 3> camera_axes(const CameraFrame& frame) {
  // The renderer's look-at frame (render::look_at): s = f × up, u = s × f.
  const Vec3 forward = geometry::normalized(frame.target - frame.eye);
  const Vec3 right = geometry::normalized(geometry::cross(forward, frame.up));
  return {right, geometry::cross(right, forward), -1.0 * forward};
}

std::array<double, 4> camera_rotation(const CameraFrame& frame) {
  // The rotation matrix has the camera's axes as columns; its quaternion (Shepperd's method).
  const auto [x, y, z] = camera_axes(frame);
  const double m[3][3] = {{x.x, y.x, z.x}, {x.y, y.y, z.y}, {x.z, y.z, z.z}};
  const double trace = m[0][0] + m[1][1] + m[2][2];
  std::array<double, 4> q{};
  if (trace > 0.0) {
    const double s = 2.0 * std::sqrt(1.0 + trace);
    q = {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
    q = {0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s};
  } else if (m[1][1] > m[2][2]) {
    const double s = 2.0 * std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
    q = {(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
    q = {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

std::vector<std::vector<Vec3>> vertex_velocities(const std::vector<std::vector<Vec3>>& frames,
                                                 const std::vector<double>& times_s) {
  if (frames.size() != times_s.size()) throw InputError("velocities: one time per frame is needed");
  std::vector<std::vector<Vec3>> v(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (frames[k].size() != frames.front().size())
      throw InputError("velocities: frame " + std::to_string(k) + " has another vertex count");
    if (k > 0 && !(times_s[k] > times_s[k - 1])) throw InputError("velocities: times must increase");
    if (frames.size() == 1) {
      v[k].assign(frames[k].size(), Vec3{});
      continue;
    }
    const std::size_t a = k == 0 ? 0 : k - 1, b = std::min(k + 1, frames.size() - 1);
    const double dt = times_s[b] - times_s[a];
    v[k].resize(frames[k].size());
    for (std::size_t i = 0; i < frames[k].size(); ++i) v[k][i] = (1.0 / dt) * (frames[b][i] - frames[a][i]);
  }
  return v;
}

}  // namespace jellysim::io
