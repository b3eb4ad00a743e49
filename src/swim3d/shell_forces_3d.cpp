#include "jellysim/swim3d/shell_forces_3d.hpp"

#include <stdexcept>

namespace jellysim::swim3d {

namespace {

shell::Vector stacked(std::span<const ib3d::Vec3> x) {
  shell::Vector v(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) v(static_cast<Eigen::Index>(3 * i + c)) = x[i][c];
  return v;
}

void unstack_into(const shell::Vector& v, std::span<ib3d::Vec3> out) {
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) out[i][c] = v(static_cast<Eigen::Index>(3 * i + c));
}

void check_size(const shell::ShellBell& bell, std::size_t markers) {
  if (static_cast<Eigen::Index>(3 * markers) != bell.rest_positions().size())
    throw std::invalid_argument("ShellForces3d: " + std::to_string(markers) + " markers for a shell of " +
                                std::to_string(bell.rest_positions().size() / 3) + " points");
}

}  // namespace

void ShellForces3d::forces(double t_s, std::span<const ib3d::Vec3> x, std::span<ib3d::Vec3> f) const {
  check_size(*bell_, x.size());
  bell_->actuate(t_s);
  shell::Vector force = shell::Vector::Zero(3 * static_cast<Eigen::Index>(x.size()));
  shell::add_elastic_forces(bell_->body(), stacked(x), force);
  unstack_into(force, f);
}

// K dx = −(∂²W/∂x²) dx: the shell's matrix-free stiffness product, negated.
void ShellForces3d::jacobian_times(double t_s, std::span<const ib3d::Vec3> x, std::span<const ib3d::Vec3> dx,
                                   std::span<ib3d::Vec3> df) const {
  check_size(*bell_, x.size());
  bell_->actuate(t_s);
  unstack_into(-shell::stiffness_times(bell_->body(), stacked(x), stacked(dx)), df);
}

bool ShellForces3d::stiffness(double t_s, std::span<const ib3d::Vec3> x, Eigen::SparseMatrix<double>& k) const {
  check_size(*bell_, x.size());
  bell_->actuate(t_s);
  k = -shell::stiffness_matrix(bell_->body(), stacked(x));
  return true;
}

std::vector<ib3d::Vec3> shell_markers(const shell::ShellBell& bell, const ib3d::Vec3& offset) {
  const shell::Vector& rest = bell.rest_positions();
  std::vector<ib3d::Vec3> x(static_cast<std::size_t>(rest.size() / 3));
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) x[i][c] = rest(static_cast<Eigen::Index>(3 * i + c)) + offset[c];
  return x;
}

}  // namespace jellysim::swim3d
