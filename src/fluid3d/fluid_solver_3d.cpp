#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/fluid/limited_flux.hpp"
#include "jellysim/fluid3d/fluid_solver_3d.hpp"

#include "advection_3d.hpp"

namespace jellysim::fluid3d {

namespace {

using fluid::ConvectionScheme;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The flux through the low side (along axis D) of component C's control volume at face I: the
// carrier (u_D averaged to that side) times the limited upwind-biased value of q = u_C there. The
// high side of face I is the low side of face I + stride(D), so each side flux is computed once.
template <ConvectionScheme S, int C, int D>
void low_side_flux_row(const Grid3d& g, const Velocity3d& vel, Field3d& flux, std::size_t I0, std::size_t I1) {
  const Field3d& q = vel.c[C];
  const Field3d& ud = vel.c[D];
  const std::size_t s = g.stride(D), sc = g.stride(C);
  for (std::size_t I = I0; I < I1; ++I) {
    const double carrier = C == D ? 0.5 * (q[I - s] + q[I]) : 0.5 * (ud[I - sc] + ud[I]);
    flux[I] = fluid::limited_flux<S>(carrier, q[I - 2 * s], q[I - s], q[I], q[I + s]);
  }
}

template <ConvectionScheme S, int C>
void low_side_flux_row(int d, const Grid3d& g, const Velocity3d& vel, Field3d& flux, std::size_t I0, std::size_t I1) {
  if (d == 0) low_side_flux_row<S, C, 0>(g, vel, flux, I0, I1);
  if (d == 1) low_side_flux_row<S, C, 1>(g, vel, flux, I0, I1);
  if (d == 2) low_side_flux_row<S, C, 2>(g, vel, flux, I0, I1);
}

// The side fluxes along axis d of component c (fluid::ConvectionScheme S) on faces [I0, I1).
template <ConvectionScheme S>
void low_side_flux_row(int c, int d, const Grid3d& g, const Velocity3d& vel, Field3d& flux, std::size_t I0, std::size_t I1) {
  if (c == 0) low_side_flux_row<S, 0>(d, g, vel, flux, I0, I1);
  if (c == 1) low_side_flux_row<S, 1>(d, g, vel, flux, I0, I1);
  if (c == 2) low_side_flux_row<S, 2>(d, g, vel, flux, I0, I1);
}

// ∇²q at face I (seven points; the ghosts carry the walls).
double face_laplacian_3d(const Grid3d& g, const Field3d& q, std::size_t I) {
  double sum = 0.0;
  for (int d = 0; d < 3; ++d) {
    const std::size_t s = g.stride(d);
    sum += (q[I + s] - 2.0 * q[I] + q[I - s]) / (g.h(d) * g.h(d));
  }
  return sum;
}

// The CPU backend: both methods (Eulerian, semi-Lagrangian) share the projection, the threads and
// the fields.
class CpuFluidSolver3d final : public FluidSolver3d {
 public:
  CpuFluidSolver3d(const Grid3d& g, const FluidSettings3d& s)
      : settings_(s), state_(g), body_(g), predictor_(g),
        fluxes_{Field3d(g.padded_size(), 0.0), Field3d(g.padded_size(), 0.0), Field3d(g.padded_size(), 0.0)},
        rhs_(g.padded_size(), 0.0), phi_(g.padded_size(), 0.0),
        pool_(resolve_threads(s.threads)),
        pressure_(make_pressure_solver_3d(s.pressure_solver, g, s.boundaries, s.pressure, &pool_)) {}

  const FlowState3d& state() const override { return state_; }
  FlowState3d& mutable_state() override { return state_; }
  Velocity3d& body_acceleration() override { return body_; }
  PressureReport3d last_pressure_report() const override { return report_; }
  StepTimings3d last_timings() const override { return timings_; }
  const FluidSettings3d& settings() const override { return settings_; }
  void archive(core::StateArchive& a) override {
    const core::StateArchive::Scope scope(a, "fluid3d");
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    for (std::size_t c = 0; c < 3; ++c) {
      a.values(std::string("velocity_") + kAxis[c], std::span<double>(state_.velocity.c[c]));
      a.values(std::string("body_acceleration_") + kAxis[c], std::span<double>(body_.c[c]));
    }
    a.values("pressure", std::span<double>(state_.pressure));
    a.values("potential", std::span<double>(phi_));  // an iterative pressure solver's first guess
    a.value("time", state_.time_s);
  }
  double stable_time_step() const override;
  void step(double dt_s) override;

 private:
  const Grid3d& grid() const { return state_.grid; }
  template <class Row>
  void for_face_rows(int c, Row&& row, int extend_axis = -1);
  template <class Row>
  void for_cell_rows(Row&& row);
  template <class Face>
  void for_face_cells(int c, Face&& face);
  void single_step(double dt_s);
  void predict_convection(double dt_s);
  void predict_advection(double dt_s);
  void predict_viscosity(double dt_s);
  void project(double dt_s);
  double largest_speed(int c) const;

  FluidSettings3d settings_;
  FlowState3d state_;
  Velocity3d body_, predictor_;
  std::array<Field3d, 3> fluxes_;  ///< convective side fluxes along x, y, z (scratch)
  Field3d rhs_, phi_;
  WorkerPool pool_;
  std::unique_ptr<PressureSolver3d> pressure_;
  PressureReport3d report_{};
  StepTimings3d timings_{};
};

// Calls row(I0, I1) for the unknown faces of component c, one x-row (fixed j, k) at a time, the
// rows split between the pool's threads; with extend_axis, one face further along that axis.
template <class Row>
void CpuFluidSolver3d::for_face_rows(int c, Row&& row, int extend_axis) {
  const Grid3d& g = grid();
  auto rx = unknown_range(g, settings_.boundaries, c, 0), ry = unknown_range(g, settings_.boundaries, c, 1),
       rz = unknown_range(g, settings_.boundaries, c, 2);
  if (extend_axis >= 0) ++(extend_axis == 0 ? rx : extend_axis == 1 ? ry : rz)[1];
  const std::size_t ny = static_cast<std::size_t>(ry[1] - ry[0]), rows = ny * static_cast<std::size_t>(rz[1] - rz[0]);
  pool_.run(rows, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t r = begin; r < end; ++r) {
      const int j = ry[0] + static_cast<int>(r % ny), k = rz[0] + static_cast<int>(r / ny);
      row(g.index(rx[0], j, k), g.index(rx[1], j, k));
    }
  });
}

// Calls face(I, i, j, k) for every unknown face of component c, the rows split between the threads.
template <class Face>
void CpuFluidSolver3d::for_face_cells(int c, Face&& face) {
  const Grid3d& g = grid();
  const int i0 = unknown_range(g, settings_.boundaries, c, 0)[0];
  for_face_rows(c, [&](std::size_t I0, std::size_t I1) {
    const int j = static_cast<int>((I0 / g.stride(1)) % (static_cast<std::size_t>(g.n(1)) + 1 + 2 * Grid3d::ghosts)) - Grid3d::ghosts;
    const int k = static_cast<int>(I0 / g.stride(2)) - Grid3d::ghosts;
    for (std::size_t I = I0; I < I1; ++I) face(I, i0 + static_cast<int>(I - I0), j, k);
  });
}

// Calls row(j, k) for every x-row of interior cells, split between the pool's threads.
template <class Row>
void CpuFluidSolver3d::for_cell_rows(Row&& row) {
  const Grid3d& g = grid();
  const std::size_t ny = static_cast<std::size_t>(g.n(1)), rows = ny * static_cast<std::size_t>(g.n(2));
  pool_.run(rows, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t r = begin; r < end; ++r) row(static_cast<int>(r % ny), static_cast<int>(r / ny));
  });
}

double CpuFluidSolver3d::largest_speed(int c) const {
  const Grid3d& g = grid();
  const Field3d& q = state_.velocity.c[static_cast<std::size_t>(c)];
  double m = settings_.boundaries.largest_wall_speed(c);
  for (int k = 0; k <= g.n(2); ++k)
    for (int j = 0; j <= g.n(1); ++j)
      for (int i = 0; i <= g.n(0); ++i) {
        const double a = std::abs(q[g.index(i, j, k)]);
        if (std::isnan(a)) return a;  // makes the step limit NaN: the step refuses it
        m = std::max(m, a);
      }
  return m;
}

// Eulerian: Δt = τ / (2 Σ_d max|u_d|/h_d + 2ν Σ_d 1/h_d²); semi-Lagrangian: the smaller of
// τ / (2ν Σ_d 1/h_d²) and cfl · min_d h_d / max_d max|u_d|. 0 for a non-finite velocity.
double CpuFluidSolver3d::stable_time_step() const {
  const bool eulerian = settings_.method == FluidMethod3d::eulerian;
  double rate = 0.0, viscous_rate = 0.0, speed = 0.0, h_min = grid().h(0);
  for (int d = 0; d < 3; ++d) {
    const double h = grid().h(d), u = largest_speed(d);
    rate += 2.0 * u / h;
    viscous_rate += 2.0 * settings_.viscosity_m2_per_s / (h * h);
    speed = std::max(speed, u);
    h_min = std::min(h_min, h);
  }
  if (!std::isfinite(rate + speed)) return 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  if (eulerian) return rate + viscous_rate > 0.0 ? settings_.safety_factor / (rate + viscous_rate) : inf;
  const double viscous = viscous_rate > 0.0 ? settings_.safety_factor / viscous_rate : inf;
  return std::min(viscous, speed > 0.0 ? settings_.cfl * h_min / speed : inf);
}

// u* = u + Δt (a − ∇·(u u)) on the unknown faces, ∇·(u u) = Σ_d (F_d⁺ − F_d⁻)/h_d in flux form
// (summed x, y, z); the other faces keep u (walls, periodic copies).
void CpuFluidSolver3d::predict_convection(double dt_s) {
  const Grid3d& g = grid();
  const bool koren = settings_.convection == ConvectionScheme::koren;
  for (int c = 0; c < 3; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c);
    for (int d = 0; d < 3; ++d) {
      Field3d& flux = fluxes_[static_cast<std::size_t>(d)];
      for_face_rows(c, [&](std::size_t I0, std::size_t I1) {
        if (koren)
          low_side_flux_row<ConvectionScheme::koren>(c, d, g, state_.velocity, flux, I0, I1);
        else
          low_side_flux_row<ConvectionScheme::van_leer>(c, d, g, state_.velocity, flux, I0, I1);
      }, d);
    }
    const Field3d& q = state_.velocity.c[cc];
    const Field3d& a = body_.c[cc];
    Field3d& f = predictor_.c[cc];
    f = q;
    const std::size_t sy = g.stride(1), sz = g.stride(2);
    const double ix = 1.0 / g.h(0), iy = 1.0 / g.h(1), iz = 1.0 / g.h(2);
    const Field3d &fx = fluxes_[0], &fy = fluxes_[1], &fz = fluxes_[2];
    for_face_rows(c, [&](std::size_t I0, std::size_t I1) {
      for (std::size_t I = I0; I < I1; ++I) {
        double conv = (fx[I + 1] - fx[I]) * ix;
        conv += (fy[I + sy] - fy[I]) * iy;
        conv += (fz[I + sz] - fz[I]) * iz;
        f[I] = q[I] + dt_s * (a[I] - conv);
      }
    });
  }
}

// u* = A(u) + Δt a: each component traced back along the characteristics (midpoint), with
// MacCormack's correction φ̂ + ½(φ − A⁻¹φ̂) clamped to the back-trace's sample range.
void CpuFluidSolver3d::predict_advection(double dt_s) {
  const Grid3d& g = grid();
  const Boundaries3d& b = settings_.boundaries;
  const Velocity3d& vel = state_.velocity;
  const bool maccormack = settings_.advection == fluid::AdvectionScheme::maccormack;
  Field3d &lo = fluxes_[0], &hi = fluxes_[1], &corrected = fluxes_[2];
  for (int c = 0; c < 3; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c);
    Field3d& f = predictor_.c[cc];  // φ̂ first
    f = vel.c[cc];
    for_face_cells(c, [&](std::size_t I, int i, int j, int k) {
      f[I] = sample_face_field(g, b, c, vel.c[cc], trace_midpoint(g, b, vel, g.position(c, i, j, k), -dt_s), &lo[I], &hi[I]);
    });
    apply_velocity_boundaries(g, b, c, f);
    if (maccormack)
      for_face_cells(c, [&](std::size_t I, int i, int j, int k) {
        const double back = sample_face_field(g, b, c, f, trace_midpoint(g, b, vel, g.position(c, i, j, k), dt_s));
        corrected[I] = std::clamp(f[I] + 0.5 * (vel.c[cc][I] - back), lo[I], hi[I]);
      });
    const Field3d& a = body_.c[cc];
    for_face_cells(c, [&](std::size_t I, int, int, int) { f[I] = (maccormack ? corrected[I] : f[I]) + dt_s * a[I]; });
  }
}

// u* += Δt ν∇²u (explicit).
void CpuFluidSolver3d::predict_viscosity(double dt_s) {
  const Grid3d& g = grid();
  const double nu_dt = settings_.viscosity_m2_per_s * dt_s;
  for (int c = 0; c < 3; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c);
    const Field3d& q = state_.velocity.c[cc];
    Field3d& f = predictor_.c[cc];
    for_face_rows(c, [&](std::size_t I0, std::size_t I1) {
      for (std::size_t I = I0; I < I1; ++I) f[I] += nu_dt * face_laplacian_3d(g, q, I);
    });
    apply_velocity_boundaries(g, settings_.boundaries, c, f);
  }
}

// ∇²φ = ∇·u*/Δt, u = u* − Δt∇φ, p = ρφ.
void CpuFluidSolver3d::project(double dt_s) {
  const Grid3d& g = grid();
  for_cell_rows([&](int j, int k) {
    for (int i = 0; i < g.n(0); ++i) rhs_[g.index(i, j, k)] = divergence_at(g, predictor_, i, j, k) / dt_s;
  });
  report_ = pressure_->solve(rhs_, phi_);
  for (int c = 0; c < 3; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c), s = g.stride(c);
    const double scale = dt_s / g.h(c);
    const Field3d& f = predictor_.c[cc];
    Field3d& q = state_.velocity.c[cc];
    for_face_rows(c, [&](std::size_t I0, std::size_t I1) {
      for (std::size_t I = I0; I < I1; ++I) q[I] = f[I] - scale * (phi_[I] - phi_[I - s]);
    });
    apply_velocity_boundaries(g, settings_.boundaries, c, q);
  }
  const double rho = settings_.density_kg_per_m3;
  for (std::size_t n = 0; n < phi_.size(); ++n) state_.pressure[n] = rho * phi_[n];
}

void CpuFluidSolver3d::single_step(double dt_s) {
  const auto t0 = Clock::now();
  apply_velocity_boundaries(grid(), settings_.boundaries, state_.velocity);
  if (settings_.method == FluidMethod3d::semi_lagrangian)
    predict_advection(dt_s);
  else
    predict_convection(dt_s);
  const auto t1 = Clock::now();
  predict_viscosity(dt_s);
  const auto t2 = Clock::now();
  project(dt_s);
  timings_ = {std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
              seconds_since(t2), seconds_since(t0)};
  state_.time_s += dt_s;
}

void CpuFluidSolver3d::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("FluidSolver3d::step: the time step must be positive");
  double left = dt_s;
  while (left > 0.0) {
    const double limit = stable_time_step();
    if (!(limit > 0.0)) throw std::runtime_error("3D fluid: the velocity is no longer finite");
    const double pieces = std::ceil(left / limit * (1.0 - 1e-12));
    const double h = pieces <= 1.0 ? left : left / pieces;
    single_step(h);
    left = pieces <= 1.0 ? 0.0 : left - h;
  }
}

}  // namespace

double divergence_at(const Grid3d& g, const Velocity3d& vel, int i, int j, int k) {
  const std::size_t I = g.index(i, j, k);
  double sum = 0.0;
  for (int d = 0; d < 3; ++d) {
    const Field3d& q = vel.c[static_cast<std::size_t>(d)];
    sum += (q[I + g.stride(d)] - q[I]) / g.h(d);
  }
  return sum;
}

double max_divergence(const Grid3d& g, const Velocity3d& vel) {
  double m = 0.0;
  for_each_interior_cell(g, [&](std::size_t, int i, int j, int k) { m = std::max(m, std::abs(divergence_at(g, vel, i, j, k))); });
  return m;
}

double kinetic_energy_3d(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const Field3d& q = vel.c[static_cast<std::size_t>(c)];
    // Each face once: along its own axis all n + 1 faces between walls (the wall faces carry 0),
    // n across a periodic axis.
    const int n_own = g.n(c) + (b.axis[static_cast<std::size_t>(c)].periodic ? 0 : 1);
    for (int k = 0; k < (c == 2 ? n_own : g.n(2)); ++k)
      for (int j = 0; j < (c == 1 ? n_own : g.n(1)); ++j)
        for (int i = 0; i < (c == 0 ? n_own : g.n(0)); ++i) sum += q[g.index(i, j, k)] * q[g.index(i, j, k)];
  }
  return 0.5 * sum * g.cell_volume();
}

std::uint64_t estimated_memory_bytes_3d(const Grid3d& g, const FluidSettings3d& s) {
  // velocity, body acceleration, predictor, convective fluxes (3 each), pressure, φ, right-hand side
  const std::uint64_t padded = static_cast<std::uint64_t>(g.padded_size()) * sizeof(double);
  // FFT: two compact buffers (fft_pressure_3d.cpp's layouts); CG: three padded fields; multigrid:
  // three per level, the levels together under 8/7 of the finest, and the coarsest level's CG
  // (bounded by the same).
  const std::uint64_t pressure_solver = s.pressure_solver == "fft"
                                            ? 2 * static_cast<std::uint64_t>(g.cell_count()) * sizeof(double)
                                            : (s.pressure_solver == "cg" ? 3 * padded : 6 * padded);
  return 15 * padded + pressure_solver;
}

std::unique_ptr<FluidSolver3d> make_fluid_solver_3d(const Grid3d& g, const FluidSettings3d& s) {
  s.boundaries.validate();
  if (s.convection == ConvectionScheme::donor_cell)
    throw std::invalid_argument("3D fluid: convection must be van-leer or koren (the limited second-order schemes)");
  if (s.advection != fluid::AdvectionScheme::linear && s.advection != fluid::AdvectionScheme::maccormack)
    throw std::invalid_argument("3D fluid: advection must be linear or maccormack");
  if (!(s.cfl > 0.0)) throw std::invalid_argument("3D fluid: cfl must be positive");
  if (!(s.density_kg_per_m3 > 0.0) || !(s.viscosity_m2_per_s >= 0.0) || !(s.safety_factor > 0.0 && s.safety_factor <= 1.0))
    throw std::invalid_argument("3D fluid: density > 0, viscosity >= 0 and 0 < safety factor <= 1 are needed");
  const std::uint64_t bytes = estimated_memory_bytes_3d(g, s), budget = core::memory_budget_bytes();
  if (bytes > budget) {
    std::ostringstream msg;
    msg << "the 3D fluid on " << g.n(0) << " x " << g.n(1) << " x " << g.n(2) << " cells needs about "
        << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB, more than the memory budget ("
        << static_cast<double>(budget) / (1024.0 * 1024.0) << " MiB, " << core::memory_budget().source << ")";
    throw InputError(msg.str());
  }
  return std::make_unique<CpuFluidSolver3d>(g, s);
}

}  // namespace jellysim::fluid3d
