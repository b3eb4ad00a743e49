#pragma once
// Adapts a Body to the ODE interface (eq. 2.19): y = [x_0x, x_0y, x_1x, ..., v_0x, v_0y, ...].
#include "jellysim/elastic/body.hpp"
#include "jellysim/ode/ode_system.hpp"

namespace jellysim::elastic {

class ElasticSystem final : public ode::OdeSystem {
 public:
  /// The body is referenced, not copied: its topology and parameters may change between steps
  /// (e.g. muscle rest lengths), but its point count must not.
  explicit ElasticSystem(const Body& body);

  Eigen::Index dimension() const override;
  Eigen::Index position_size() const override;
  bool has_jacobian() const override { return true; }

  /// Packs the body's current positions and velocities into a state vector.
  ode::Vector pack_state() const;
  /// Writes a state vector back into the body's points (prescribed points follow their motion at t).
  static void unpack_state(const ode::Vector& y, double t, Body& body);

 protected:
  void compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const override;
  /// df/dy = [[0, I], [M⁻¹ ∂F/∂x, M⁻¹ ∂F/∂v]], rows of pinned/prescribed points zero. Forces use a
  /// prescribed point's position from its motion at t, not from y, so its columns are zero too.
  void compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const override;

 private:
  const Body& body_;
  mutable std::vector<Vec2> x_, v_, f_;
  mutable std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace jellysim::elastic
