#pragma once
// Peskin's immersed boundary method (thesis §4.3.2): the points of a spring-mass body are
// massless markers carried by the fluid (eq. 4.20); their spring forces are spread onto the grid
// as a body acceleration F/(ρΔxΔy) (eq. 4.19). Two time-stepping schemes:
//  * explicit (the thesis's): forces from the positions at the start of the step;
//  * semi-implicit (beyond the thesis, which names it as future work): the forces are those at the
//    end of the step, linearised, F(X + ΔX) ≈ F + KΔX, with ΔX = Δt·u^{n+1}(X) found by GMRES
//    where every operator application spreads, projects and interpolates (the fluid's true
//    response to a point force, pressure included). This is backward Euler for the stiff
//    elastic–fluid exchange; on the default jellyfish it stays stable at 8 times the explicit
//    scheme's largest step (docs/jellyfish.md).
#include <numbers>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "jellysim/core/parallel.hpp"
#include "jellysim/ode/gmres.hpp"
#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/coupling/mobility.hpp"
#include "jellysim/elastic/body.hpp"
#include "jellysim/fluid/fluid_solver.hpp"

namespace jellysim::coupling {

enum class Scheme { explicit_euler, semi_implicit };
std::string_view to_string(Scheme s);
/// "explicit" or "semi-implicit"; nullopt otherwise.
std::optional<Scheme> scheme_from_string(std::string_view name);
/// The schemes' names (ImmersedBoundary::schemes), for scene files' choices.
std::vector<std::string> scheme_names();

/// How the semi-implicit scheme's GMRES is preconditioned.
enum class Preconditioner {
  none,      ///< plain GMRES: one projection per iteration, tens of iterations on fine grids
  mobility,  ///< the dense marker-space operator I − Δt² R K (mobility.hpp), LU-factored (right);
             ///< on axisymmetric water from AxisymmetricMobility
};
std::string_view to_string(Preconditioner p);
/// "none" or "mobility"; nullopt otherwise.
std::optional<Preconditioner> preconditioner_from_string(std::string_view name);

struct CouplingSettings {
  Kernel kernel = Kernel::bilinear;
  Scheme scheme = Scheme::semi_implicit;
  double safety_factor = 0.5;      ///< τ: Δt = τ·min(eq. 4.8, eq. 4.9), then clamped below
  double max_time_step_s = 1.0 / 60.0;  ///< upper bound on Δt (also used while the fluid is at rest)
  double min_time_step_s = 1e-6;   ///< a smaller Δt means the run cannot go on
  double krylov_tolerance = 1e-6;  ///< relative residual of the semi-implicit GMRES solve
  int krylov_max_iterations = 200;
  Preconditioner preconditioner = Preconditioner::mobility;
  /// The mobility R is rebuilt when a marker has moved this many cells since the last build
  /// (0: every step, when R is exact and GMRES needs one iteration).
  double mobility_rebuild_cells = 0.0;
  /// Threads that build the planar R (0: one per core, or one inside a sweep's or batch's run;
  /// resolve_threads). R, and so every result, is the same whatever the number.
  int threads = 1;
  /// The fluid's west side is a mirror plane (the half tank of a mirror-symmetric scene): markers
  /// west of it and stencils reaching across it read the mirror image of the flow.
  bool west_mirror = false;
};

/// Limits whose violation stops a run (thesis §8.1.4's two kinds of instability).
struct StabilityLimits {
  double max_speed_m_per_s = 2.0;  ///< numerical: fluid or point speed above this is a blow-up
  double max_strain = 1.25;        ///< structural: |l/l_r − 1| of any linear spring
  double max_bend_rad = 143.0 * std::numbers::pi / 180.0;  ///< structural: |θ − θ_r| of any angular spring (a fold)
};

/// Sets time-dependent parameters of the body (muscle rest lengths) for time t.
using Actuator = std::function<void(double t, elastic::Body& body)>;

struct CoupledStepReport {
  double dt_s = 0.0;
  fluid::StepReport fluid{};
  ode::GmresReport krylov{};  ///< semi-implicit scheme only
};

class ImmersedBoundary {
 public:
  /// The fluid solver and body are referenced and advanced in place. The body's free points are
  /// the markers; their masses, drag and gravity are ignored (the body is neutrally buoyant and its
  /// mass is the fluid's, §4.3.2). Pinned and prescribed points are target points: they are not
  /// carried by the fluid and pass no force to it, but springs tie markers to them (rigid
  /// obstacles held in place or moved on a path).
  ImmersedBoundary(fluid::FluidSolver& fluid, elastic::Body& body, const CouplingSettings& settings,
                   Actuator actuator = {});

  /// A coupling scheme: the name scene files give it (`coupling.scheme`) and its step.
  struct SchemeEntry {
    Scheme scheme;
    std::string_view name;
    CoupledStepReport (ImmersedBoundary::*step)(double dt_s);
  };
  /// The schemes: the one table that names, parses and runs them (to_string, scheme_from_string, step).
  static std::span<const SchemeEntry> schemes();

  double time_s() const { return time_s_; }
  long steps() const { return steps_; }
  const CouplingSettings& settings() const { return settings_; }
  fluid::FluidSolver& fluid() { return fluid_; }
  const elastic::Body& body() const { return body_; }
  /// R = J P S / ρ built column by column, one spread-project-interpolate per unknown (2N
  /// projections, any pressure solver): the reference the mobility matrix is tested against.
  /// With the mirror symmetry, R on the symmetric unknowns (pick R Q: one projection per unknown).
  Eigen::MatrixXd response_by_projections();
  /// How often the mobility preconditioner's R was built (for benchmarks).
  long mobility_builds() const { return mobility_builds_; }

  /// Δt = τ·min(eqs. 4.8, 4.9) from the current fluid and marker speeds, at most max_time_step_s.
  double next_time_step() const;
  /// Advances fluid and markers by dt_s; the markers' velocities are stored in body().points.velocity.
  CoupledStepReport step(double dt_s);
  /// Takes over another coupling's clock, step count and last increment (the same body on a new
  /// fluid, e.g. the whole tank after its half).
  void continue_from(const ImmersedBoundary& earlier);
  /// Call after adding points to the body or changing their kinds.
  void refresh_markers();
  /// The body and flow are their own mirror images about a vertical line, partners[p] being the
  /// mirror image of point p (elastic/body_mirror.hpp): the solve then looks for a symmetric increment
  /// and the preconditioner works on the symmetric unknowns only (half of them). Empty: no symmetry.
  void set_mirror_symmetry(std::vector<int> partners);
  /// Checkpoints (core/state_archive.hpp): the clock, the step count, the last increment (GMRES's
  /// first guess), the response projections' last pressure and, when R is kept between steps
  /// (mobility_rebuild_cells > 0), R and where it was built. The fluid and body are the caller's.
  void archive(core::StateArchive& a);


 private:
  CoupledStepReport step_explicit(double dt_s);
  CoupledStepReport step_semi_implicit(double dt_s);
  /// What one semi-implicit step carries from stage to stage.
  struct SemiImplicitStep {
    double dt = 0.0, dt2 = 0.0;
    Eigen::VectorXd f0;                     ///< F at x^n, rest lengths at t + Δt
    Eigen::SparseMatrix<double> stiffness;  ///< K = ∂F/∂X at x^n
    bool merged = false;                    ///< the guess's forces ride with the fluid's projection
    Eigen::VectorXd x0;                     ///< the increment's guess
    Eigen::VectorXd rhs;                    ///< b − A x0
    Eigen::VectorXd correction;             ///< e = ΔX − x0
    Eigen::VectorXd coefficients;           ///< GMRES's, of the operator applications
    std::size_t applied = 0;                ///< operator applications (their fields in basis_fields_)
  };
  /// Stage 1: F and K at x^n (rest lengths at t + Δt), the guess x0, whether the fluid step takes
  /// the guess's forces along.
  void linearise_forces(double dt_s, SemiImplicitStep& s);
  /// Stage 2: the fluid over the step (u_L) and its velocity U_L at the markers.
  fluid::StepReport predict_fluid(SemiImplicitStep& s);
  /// Stage 3: the right-hand side b − A x0 of the increment's equation.
  void build_right_hand_side(SemiImplicitStep& s);
  /// Stage 4: GMRES (preconditioned by the marker-space solve) for e; ΔX = x0 + e.
  ode::GmresReport solve_increment(SemiImplicitStep& s);
  /// Stage 5: u^{n+1} = u_L + Δt P S (F + K ΔX) / ρ from the fields GMRES kept.
  void apply_end_of_step_forces(const SemiImplicitStep& s, const ode::GmresReport& krylov);
  void compute_forces(std::vector<Vec2>& force) const;
  void assemble_stiffness(Eigen::SparseMatrix<double>& k) const;
  /// velocity_at_markers = J P S (forces)/ρ: the divergence-free velocity change per second that
  /// the given marker forces cause, interpolated back at the markers.
  void apply_response(const Eigen::VectorXd& forces, Eigen::VectorXd& velocity_at_markers);
  /// Spreads forces into scratch_.velocity as accelerations and makes them divergence-free.
  void project_spread_forces(std::span<Vec2> forces);
  /// w = S F / ρ on the interior faces (eq. 4.19), zero elsewhere; target points spread nothing.
  void spread_to_interior_faces(std::span<Vec2> forces, fluid::Velocity& w);
  /// Axisymmetric flow (fluid::Geometry): every marker is a ring about the axis (transfer_kernels.hpp).
  bool axisymmetric() const { return fluid_.settings().geometry == fluid::Geometry::axisymmetric; }
  /// Spreads marker forces as accelerations onto the faces (planar or ring form).
  void spread(std::span<const Vec2> points, std::span<const Vec2> forces, fluid::FaceAccelerations& acc) const;
  /// The tank's periodic axes: the kernel wraps around their seams.
  Periodicity periodicity() const { return {homogeneous_.periodic_x(), homogeneous_.periodic_y()}; }
  /// Where target point p is at time t (pinned: where it is; prescribed: on its path).
  Vec2 target_position(std::size_t p, double t) const;
  /// Zeroes the entries of target points: they spread no force and are not moved by the fluid.
  void mask_target_forces(std::span<Vec2> values) const;
  void move_markers_with_fluid(double dt_s);
  /// Fluid velocity at every marker (interpolation, also across a mirror side).
  void interpolate_at_markers(const fluid::Velocity& vel, std::vector<Vec2>& out) const;
  /// Rebuilds R when the markers have moved far enough, then factors M = I − Δt² R K (on the
  /// mirror-symmetric unknowns when the scene is symmetric).
  void prepare_preconditioner(double dt_s, const Eigen::SparseMatrix<double>& stiffness);
  /// out = M⁻¹ in (the antisymmetric part of `in` passes unchanged when the scene is symmetric).
  void apply_preconditioner(const Eigen::VectorXd& in, Eigen::VectorXd& out) const;
  /// Factors M (preconditioner_matrix_): its rows of target points' unknowns are the identity's
  /// (their rows of R are zero), so only the block of the moving unknowns is LU-factored.
  void factor_preconditioner();
  /// M⁻¹ v on the solve's unknowns (all, or the symmetric ones), from factor_preconditioner().
  Eigen::VectorXd solve_preconditioner(const Eigen::VectorXd& v) const;
  /// Sorts the solve's unknowns into those of target points (held_) and the others (moving_).
  void split_target_unknowns();
  /// v → ½(v + mirror image of v) for marker vectors (x components odd, y even).
  void keep_symmetric_part(Eigen::VectorXd& v) const;
  /// The symmetric unknowns: Q maps them to marker increments, pick_ selects them back.
  void build_symmetric_unknowns();

  fluid::FluidSolver& fluid_;
  elastic::Body& body_;
  CouplingSettings settings_;
  Actuator actuator_;
  double time_s_ = 0.0;
  long steps_ = 0;
  fluid::Projector projector_;
  fluid::FlowState scratch_;
  fluid::Boundaries homogeneous_;
  std::vector<Vec2> force_, velocity_, work_;
  Eigen::VectorXd last_increment_;
  fluid::Velocity base_field_;                 ///< P S (F + K x0) / ρ of the current step (when not merged)
  std::vector<fluid::Velocity> basis_fields_;  ///< P S K v_k / ρ for GMRES's basis vectors v_k
  std::vector<char> is_target_;  ///< pinned or prescribed points: Peskin's target points
  bool has_targets_ = false;
  TransferGeometry transfer_;
  std::unique_ptr<MobilityMatrix> mobility_;  ///< built at the first preconditioned step
  std::unique_ptr<AxisymmetricMobility> ring_mobility_;  ///< the same on axisymmetric water
  Eigen::MatrixXd mobility_matrix_;           ///< R at mobility_points_
  std::vector<Vec2> mobility_points_;         ///< marker positions R was built for
  Eigen::PartialPivLU<Eigen::MatrixXd> preconditioner_lu_;
  long mobility_builds_ = 0;
  std::vector<int> mirror_partner_;  ///< empty unless the scene is mirror-symmetric
  std::vector<int> independent_;     ///< points p with partner ≥ p: whose rows R needs
  Eigen::SparseMatrix<double> symmetric_basis_;  ///< Q: 2N × d, symmetric unknowns → increments
  Eigen::SparseMatrix<double> pick_;              ///< d × 2N: the unknowns of a symmetric increment
  std::vector<Eigen::Index> picked_rows_;         ///< for each symmetric unknown, its row in R's rows
  Eigen::SparseMatrix<double> picked_rows_matrix_;  ///< d × (rows of R): selects picked_rows_
  Eigen::MatrixXd reduced_mobility_;                ///< R_s = (picked rows of R) Q
  Eigen::MatrixXd preconditioner_matrix_;           ///< M (or M_s), kept to avoid reallocation
  std::vector<Eigen::Index> held_, moving_;         ///< unknowns of target points, and the others
  Eigen::MatrixXd moving_block_, coupling_block_;   ///< M's rows of moving_: columns moving_, held_
  std::unique_ptr<WorkerPool> pool_;                ///< threads for R (settings_.threads), or none
};

/// Problems that should stop a run, or "" when none: "numerical instability: ..." (NaN, runaway
/// speed) or "structural instability: ..." (overstretched spring, folded joint), naming the point or
/// spring and where it is.
/// Strain is measured against strain_reference[s] when given (e.g. a muscle's uncontracted length),
/// else against the spring's current rest length.
std::string check_stability(const fluid::FlowState& flow, const elastic::Body& body, const StabilityLimits& limits,
                            const std::vector<double>* strain_reference = nullptr);

}  // namespace jellysim::coupling
