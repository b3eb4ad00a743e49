#pragma once
// The 3D incompressible Navier–Stokes solver (issue 40, part 1; docs/three-d.md). The step is behind
// an interface (`FluidSolver3d`) so that another backend (a GPU one) can be added later without
// changing its callers; `make_fluid_solver_3d` gives the CPU backend, the Eulerian method of the 2D
// solver (docs/fluids.md) in three dimensions:
//   u* = uⁿ + Δt (ν∇²uⁿ − ∇·(u u)ⁿ + a)          (forward Euler predictor on the interior faces)
//   ∇²φ = ∇·u*/Δt,  uⁿ⁺¹ = u* − Δt∇φ,  p = ρφ     (projection)
// with the convective term in flux form, each face flux carrier·q with q the limited upwind-biased
// face value of van Leer or Koren (fluid/limited_flux.hpp, Hundsdorfer & Verwer 2003, §III.1).
// Time step: Δt ≤ τ / (2 Σ_d max|u_d|/h_d + 2ν Σ_d 1/h_d²) (Courant sum ½ for the TVD forward
// Euler step, the viscous limit added as a rate, as the 2D limited schemes do).
// With `method = semi_lagrangian` the convective term is replaced by advection along the
// characteristics: u* = A(uⁿ) + Δt(ν∇²uⁿ + a), A one midpoint back-trace with trilinear sampling
// (`linear`) or with MacCormack's correction φ̂ + ½(φ − A⁻¹φ̂) clamped to the range of the eight
// samples the back-trace used (`maccormack`, Selle et al. 2008); Δt ≤ min(τ / (2ν Σ 1/h²),
// cfl · min h / max|u|). The step is first order in time (the splitting; the 2D solver's
// Crank–Nicolson trajectory step is not carried over yet).
// Threads: the predictor and the correction split the rows (j, k) between the pool's threads, each
// face computed by one thread from the same inputs, so the bytes do not depend on the thread count.
#include <cstdint>
#include <memory>
#include <string>

#include "jellysim/core/parallel.hpp"
#include "jellysim/core/state_archive.hpp"
#include "jellysim/fluid/schemes.hpp"
#include "jellysim/fluid3d/boundary_3d.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"
#include "jellysim/fluid3d/pressure_3d.hpp"

namespace jellysim::fluid3d {

enum class FluidMethod3d { eulerian, semi_lagrangian };

struct FluidSettings3d {
  FluidMethod3d method = FluidMethod3d::eulerian;
  double density_kg_per_m3 = 1000.0;
  double viscosity_m2_per_s = 1e-6;  ///< kinematic viscosity ν
  Boundaries3d boundaries = Boundaries3d::closed_box();
  fluid::ConvectionScheme convection = fluid::ConvectionScheme::koren;  ///< eulerian: van-leer or koren
  fluid::AdvectionScheme advection = fluid::AdvectionScheme::maccormack;  ///< semi-Lagrangian: linear or maccormack
  double cfl = 1.0;  ///< semi-Lagrangian: the largest max|u|Δt/h of a step
  std::string pressure_solver = "fft";                                   ///< "fft", "multigrid" or "cg"
  PressureSettings3d pressure{};
  double safety_factor = 0.5;  ///< τ in the time-step limit
  int threads = 1;             ///< pool threads (0: all cores, resolve_threads)
};

/// Wall-clock seconds the last step spent in each part (measurements, never results).
struct StepTimings3d {
  double convection_s = 0.0, viscosity_s = 0.0, pressure_s = 0.0, total_s = 0.0;
};

class FluidSolver3d {
 public:
  virtual ~FluidSolver3d() = default;
  virtual const FlowState3d& state() const = 0;
  /// The flow, to set initial conditions or edit between steps (the next step fills the ghosts
  /// again).
  virtual FlowState3d& mutable_state() = 0;
  /// The body acceleration (m/s², on the faces, the velocity's layout) added to every step until
  /// changed: the immersed boundary will spread its force / (ρ h³) here.
  virtual Velocity3d& body_acceleration() = 0;
  /// Advances by dt (s), in equal sub-steps within the stability limit when dt exceeds it. Throws
  /// std::runtime_error when the velocity is no longer finite.
  virtual void step(double dt_s) = 0;
  /// The largest stable step for the present flow (s).
  virtual double stable_time_step() const = 0;
  /// What the last step's (or sub-step's) projection reported.
  virtual PressureReport3d last_pressure_report() const = 0;
  virtual StepTimings3d last_timings() const = 0;
  virtual const FluidSettings3d& settings() const = 0;
  /// Saves or restores what a step reads from the past (the flow, the body acceleration, the
  /// clock, the last pressure potential an iterative solver starts from): checkpoints (issue 23).
  virtual void archive(core::StateArchive& a) = 0;
};

/// The bytes a solver on this grid allocates (fields, pressure solver buffers), estimated before
/// allocating them.
std::uint64_t estimated_memory_bytes_3d(const Grid3d& g, const FluidSettings3d& s);
/// The CPU solver. Throws InputError (with the estimate) when the estimate exceeds the memory
/// budget (core/memory.hpp), std::invalid_argument for bad settings.
std::unique_ptr<FluidSolver3d> make_fluid_solver_3d(const Grid3d& g, const FluidSettings3d& s);

/// ∇·u at interior cell (i, j, k) (1/s).
double divergence_at(const Grid3d& g, const Velocity3d& vel, int i, int j, int k);
/// max over the cells of |∇·u| (1/s).
double max_divergence(const Grid3d& g, const Velocity3d& vel);
/// ½ Σ |u|² h³ over the faces each component owns (J/kg · m³ = m⁵/s²; times ρ: joules).
double kinetic_energy_3d(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel);
/// Sets component c on its unknown faces and walls from f(x, y, z) and fills the ghosts.
template <class F>
void set_component(const Grid3d& g, const Boundaries3d& b, Velocity3d& vel, int c, F&& f) {
  Field3d& q = vel.c[static_cast<std::size_t>(c)];
  for (int k = 0; k <= g.n(2); ++k)
    for (int j = 0; j <= g.n(1); ++j)
      for (int i = 0; i <= g.n(0); ++i) {
        const Vec3 x = g.position(c, i, j, k);
        q[g.index(i, j, k)] = f(x[0], x[1], x[2]);
      }
  apply_velocity_boundaries(g, b, c, q);
}

}  // namespace jellysim::fluid3d
