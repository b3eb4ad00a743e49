#pragma once
// The 3D immersed boundary's coupled step (issue 40, part 2; docs/three-d.md): massless markers
// carried by the 3D fluid (eq. 4.20, X ← X + Δt J u), their forces spread into the fluid's body
// acceleration (eq. 4.19, a = S F / (ρ V)). Two schemes, as the 2D coupling has:
//  * explicit: F at the start of the step (the thesis's);
//  * semi-implicit: F at the end of the step, linearised, F(X + ΔX) ≈ F + K ΔX, with
//    ΔX = Δt J u^{n+1}. The fluid step is affine in its body acceleration (one projection of
//    u* + Δt a), so u^{n+1} = u_L + Δt P S (F + K ΔX) / (ρV) and
//        (I − Δt² R K) ΔX = Δt J u_L + Δt² R F,   R = J P S / (ρ V),
//    backward Euler for the stiff elastic–fluid exchange. Unlike the 2D code, which tabulates R
//    densely (one projection per marker unknown), the system is solved matrix-free by GMRES: one
//    operator application is one spread → projection (FFT) → interpolation; the guess's forces ride
//    with the fluid step. Optional right preconditioner: M = I − Δt² r₀ K, r₀ the marker's analytic
//    self-mobility, (d − 1)/d · (Σφ²)³ / (ρ V) — the kernel's self-overlap (Σ_i φ(r − i)² = 3/8 for
//    Peskin's 4-point function, any r) times the part of an isotropic field the projection keeps —
//    factored once per step as a sparse matrix when the force model assembles K. Measured slower than
//    plain GMRES on spring nets (docs/three-d.md), so off by default.
#include <chrono>
#include <memory>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "jellysim/core/parallel.hpp"
#include "jellysim/core/state_archive.hpp"
#include "jellysim/fluid3d/fluid_solver_3d.hpp"
#include "jellysim/fluid3d/pressure_3d.hpp"
#include "jellysim/ib3d/markers_3d.hpp"
#include "jellysim/ib3d/transfer_3d.hpp"

namespace jellysim::ib3d {

enum class Scheme3d { explicit_euler, semi_implicit };
enum class Preconditioner3d {
  none,           ///< plain GMRES
  self_mobility,  ///< M = I − Δt² r₀ K (needs ForceModel3d::stiffness; plain GMRES without it)
};
std::string_view to_string(Scheme3d s);
std::string_view to_string(Preconditioner3d p);

struct CouplingSettings3d {
  Scheme3d scheme = Scheme3d::semi_implicit;
  coupling::Kernel kernel = coupling::Kernel::peskin4;
  Preconditioner3d preconditioner = Preconditioner3d::none;  ///< self_mobility measured slower (docs/three-d.md)
  double krylov_tolerance = 1e-6;  ///< the semi-implicit solve's residual, relative to the increment ΔX
  int krylov_max_iterations = 200;
  int threads = 1;  ///< spreading and interpolation (0: all cores); the bits do not depend on it
};

struct CoupledStepReport3d {
  double dt_s = 0.0;
  int krylov_iterations = 0;       ///< semi-implicit: GMRES's operator applications
  double relative_residual = 0.0;
  bool converged = true;
  int projections = 0;             ///< pressure solves beyond the fluid step's own
  double transfer_s = 0.0, fluid_s = 0.0, krylov_s = 0.0;  ///< wall-clock split (measurements)
};

class ImmersedBoundary3d {
 public:
  /// fluid, markers and forces are referenced (and the first two advanced in place).
  ImmersedBoundary3d(fluid3d::FluidSolver3d& fluid, Markers3d& markers, const ForceModel3d& forces,
                     const CouplingSettings3d& settings = {});

  /// Advances the fluid and the markers by dt_s; markers.velocity gets J u^{n+1}, markers.force the
  /// forces spread.
  CoupledStepReport3d step(double dt_s);
  double time_s() const { return time_s_; }
  const CouplingSettings3d& settings() const { return settings_; }
  Transfer3d& transfer() { return transfer_; }
  /// r₀ = (2/3) (Σφ²)³ / (ρ V) (m/s² per N): the analytic self-mobility, R's diagonal in the open.
  double self_mobility() const;
  /// out = R f = J P S f / (ρ V): the marker accelerations (m/s²) the forces f (N, flattened
  /// x0 y0 z0 x1 …) give the fluid at rest, pressure included (one projection).
  void apply_response(const Eigen::VectorXd& f, Eigen::VectorXd& out);
  /// Saves or restores the coupling's history: its clock, the last increment (GMRES's first
  /// guess) and the markers (positions, velocities, forces); the fluid archives its own.
  void archive(core::StateArchive& a);

 private:
  CoupledStepReport3d step_explicit(double dt_s);
  CoupledStepReport3d step_semi_implicit(double dt_s);
  /// What one semi-implicit step carries from stage to stage.
  struct SemiImplicitStep {
    double dt = 0.0;
    Eigen::VectorXd x0;               ///< the increment's guess (the last increment)
    std::vector<Vec3> guess_forces;   ///< F + K x0 (N), at t + Δt
    Eigen::VectorXd rhs;              ///< Δt J u_L' − x0
    double predicted_norm = 0.0;      ///< |Δt J u_L'|: the scale of the solve's tolerance
  };
  /// Stage 1: F at (t + Δt, Xⁿ), the guess x0 and the forces F + K x0 the fluid step takes along.
  void linearise_forces(double dt_s, SemiImplicitStep& s);
  /// Stage 3 (after the fluid step): the right-hand side Δt J u_L' − x0.
  void build_right_hand_side(SemiImplicitStep& s, CoupledStepReport3d& r);
  /// Stage 5 (after the solve): u += Δt P S K e / (ρV); the markers' forces F + K ΔX.
  void apply_end_of_step_forces(const SemiImplicitStep& s, const Eigen::VectorXd& e, CoupledStepReport3d& r);
  /// Forces (N) into the fluid's body acceleration (zeroed first), then the fluid step.
  void step_fluid_with_forces(double dt_s, std::span<const Vec3> force, CoupledStepReport3d& r);
  /// Stage 4 of the semi-implicit step: GMRES for the correction e of the increment's guess.
  Eigen::VectorXd solve_correction(double dt_s, const Eigen::VectorXd& rhs, double increment_norm, CoupledStepReport3d& r);
  /// M = I − Δt² r₀ K factored; false when the model gives no K (or no preconditioner is asked).
  bool prepare_preconditioner(double dt_s);
  /// scratch_ = P S f / (ρ V) with homogeneous boundaries (forces on unknown faces only).
  void project_spread(std::span<const Vec3> force);
  void project(fluid3d::Velocity3d& w);
  /// X += Δt J u, velocity = J u.
  void move_markers(double dt_s);

  fluid3d::FluidSolver3d& fluid_;
  Markers3d& markers_;
  const ForceModel3d& forces_;
  CouplingSettings3d settings_;
  std::unique_ptr<WorkerPool> pool_;
  fluid3d::Boundaries3d homogeneous_;  ///< the fluid's boundaries with walls at rest
  Transfer3d transfer_;
  std::unique_ptr<fluid3d::PressureSolver3d> pressure_;
  fluid3d::Velocity3d scratch_;
  fluid3d::Field3d rhs_, phi_;
  std::vector<Vec3> work_, velocity_;
  Eigen::VectorXd last_increment_;
  Eigen::SparseMatrix<double> stiffness_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> preconditioner_;
  double time_s_ = 0.0;
};

/// Flattens marker vectors to x0 y0 z0 x1 … and back.
Eigen::VectorXd flatten(std::span<const Vec3> v);
void unflatten(const Eigen::VectorXd& in, std::vector<Vec3>& out);

}  // namespace jellysim::ib3d
