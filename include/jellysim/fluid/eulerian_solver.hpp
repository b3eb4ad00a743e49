#pragma once
// The classical Eulerian method of thesis §4.1 (Griebel, Dornseifer & Neunhoeffer): explicit
// predictor F, G (eq. 4.6) with donor-cell/central convective differences blended by γ (or, beyond
// the thesis, limited upwind-biased face values: FluidSettings::convection), pressure
// Poisson equation (eq. 3.3), velocity correction (eq. 4.7), stability limits eqs. 4.8–4.9.
#include "jellysim/fluid/fluid_solver.hpp"

namespace jellysim::fluid {

class EulerianSolver final : public FluidSolver {
 public:
  EulerianSolver(const MacGrid& grid, const FluidSettings& settings);
  std::string_view name() const override { return "eulerian"; }
  /// Advances by dt_s; a Δt above stable_time_step() is refused (std::domain_error) or split
  /// into stable sub-steps according to settings().time_step_policy.
  StepReport step(double dt_s) override;
  double stable_time_step() const override;
  /// The predictor (eq. 4.6) adds Δt·a on the interior faces, then one projection.
  bool projects_body_acceleration_linearly() const override { return true; }
  /// γ used in the last step (0 with a limited convection scheme).
  double last_donor_cell_blend() const { return last_gamma_; }

 private:
  PressureSolveReport single_step(double dt_s);
  double donor_cell_blend(double dt_s) const;
  /// Eq. 4.6 on the interior faces: F = u + Δt(ν∇²u − ∂(u²)/∂x − ∂(uv)/∂y + f_x), same for G.
  void compute_predictor(double dt_s, double gamma);
  /// Eq. 4.6 with limited upwind-biased face values (settings().convection) instead of γ.
  template <ConvectionScheme S>
  void compute_limited_predictor(double dt_s);
  /// Eq. 4.6 with the convective terms at face (i, j) given by the two callables.
  template <class ConvectionU, class ConvectionV>
  void compute_predictor_with(double dt_s, ConvectionU&& convection_u_at, ConvectionV&& convection_v_at);
  /// The same with the viscous terms (ν times them) given too (the axisymmetric operators).
  template <class ConvectionU, class ConvectionV, class ViscousU, class ViscousV>
  void compute_predictor_with(double dt_s, ConvectionU&& convection_u_at, ConvectionV&& convection_v_at,
                              ViscousU&& viscous_u_at, ViscousV&& viscous_v_at);

  Velocity predictor_;
  double last_gamma_ = 0.0;
};

/// Convective term ∂(u²)/∂x + ∂(uv)/∂y at the x-face (i, j) with donor-cell weight γ
/// (Griebel et al. eq. 3.19).
double convection_u(const Velocity& vel, int i, int j, double gamma);
/// Convective term ∂(uv)/∂x + ∂(v²)/∂y at the y-face (i, j).
double convection_v(const Velocity& vel, int i, int j, double gamma);
/// The same terms with the limited face values of a van_leer or koren scheme (donor_cell: γ = 1);
/// the stencil reaches two samples upwind, wrapped along periodic axes of `b`.
double convection_u_limited(const Velocity& vel, const Boundaries& b, int i, int j, ConvectionScheme scheme);
double convection_v_limited(const Velocity& vel, const Boundaries& b, int i, int j, ConvectionScheme scheme);
/// Five-point Laplacian of a face field at (i, j) (ghosts must be filled).
double face_laplacian(const Field& f, int i, int j);

// Axisymmetric flow without swirl (x = r from the axis, y = z): u_r on the r-faces at r = iΔr
// (i ≥ 1: the axis face is a wall), u_z on the z-faces at the cell radii (i + ½)Δr.
/// (1/r) ∂/∂r (r ∂u_r/∂r) − u_r/r² + ∂²u_r/∂z² at the r-face (i, j), i ≥ 1.
double axisymmetric_viscous_u(const Field& u, int i, int j);
/// (1/r) ∂/∂r (r ∂u_z/∂r) + ∂²u_z/∂z² at the z-face (i, j); no flux through the axis.
double axisymmetric_viscous_v(const Field& v, int i, int j);
/// (1/r) ∂(r u_r²)/∂r + ∂(u_r u_z)/∂z with donor-cell weight γ.
double axisymmetric_convection_u(const Velocity& vel, int i, int j, double gamma);
/// (1/r) ∂(r u_r u_z)/∂r + ∂(u_z²)/∂z with donor-cell weight γ.
double axisymmetric_convection_v(const Velocity& vel, int i, int j, double gamma);

}  // namespace jellysim::fluid
