#include "jellysim/sph/scene.hpp"

#include "jellysim/elastic/forces.hpp"
#include "jellysim/ode/stage_sum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace jellysim::sph {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec2 get(const ode::Vector& y, std::size_t slot) {
  return {y[static_cast<Eigen::Index>(2 * slot)], y[static_cast<Eigen::Index>(2 * slot + 1)]};
}
void set(ode::Vector& y, std::size_t slot, Vec2 v) {
  y[static_cast<Eigen::Index>(2 * slot)] = v.x;
  y[static_cast<Eigen::Index>(2 * slot + 1)] = v.y;
}
bool is_free(const elastic::Body& b, std::size_t i) { return b.points.kind[i] == elastic::PointKind::Free; }

}  // namespace

void validate(const Scene& s) {
  const std::size_t n = s.position.size();
  if (s.velocity.size() != n || s.mass.size() != n || s.fluid_count > n) {
    throw std::invalid_argument("scene: particle arrays differ in size or fluid_count exceeds them");
  }
  for (double m : s.mass) {
    if (!(m > 0.0 && std::isfinite(m))) throw std::invalid_argument("scene: particle masses must be in (0, inf)");
  }
  const auto points = static_cast<int>(s.body.points.size());
  for (std::size_t k = 0; k < s.outline.size(); ++k) {
    if (s.outline.a[k] < 0 || s.outline.a[k] >= points || s.outline.b[k] < 0 || s.outline.b[k] >= points) {
      throw std::invalid_argument("scene: outline edge " + std::to_string(k) + " names a missing body point");
    }
  }
  for (elastic::PointKind kind : s.body.points.kind) {
    if (kind == elastic::PointKind::Prescribed) throw std::invalid_argument("scene: prescribed body points are not supported");
  }
  if (s.threads < 0 || s.threads > 64) throw std::invalid_argument("scene: threads must be in [0, 64] (0: one per core)");
  validate(s.sph);
}

CoupledSystem::CoupledSystem(Scene& scene)
    : scene_(scene), fluid_((validate(scene), std::make_unique<SphFluid>(scene.sph, scene.walls, resolve_threads(scene.threads)))),
      body_(scene.body) {}

Eigen::Index CoupledSystem::dimension() const {
  return static_cast<Eigen::Index>(4 * (scene_.position.size() + scene_.body.points.size()));
}

ode::Vector CoupledSystem::pack_state() const {
  const std::size_t n = scene_.position.size(), m = scene_.body.points.size(), half = n + m;
  ode::Vector y(dimension());
  for (std::size_t i = 0; i < n; ++i) {
    set(y, i, scene_.position[i]);
    set(y, half + i, scene_.velocity[i]);
  }
  for (std::size_t i = 0; i < m; ++i) {
    set(y, n + i, scene_.body.points.position[i]);
    set(y, half + n + i, scene_.body.points.velocity[i]);
  }
  return y;
}

void CoupledSystem::unpack_state(const ode::Vector& y) const {
  const std::size_t n = scene_.position.size(), m = scene_.body.points.size(), half = n + m;
  for (std::size_t i = 0; i < n; ++i) {
    scene_.position[i] = get(y, i);
    scene_.velocity[i] = get(y, half + i);
  }
  for (std::size_t i = 0; i < m; ++i) {
    scene_.body.points.position[i] = get(y, n + i);
    scene_.body.points.velocity[i] = get(y, half + n + i);
  }
}

// y' = [v; a] (eq. 2.19): SPH accelerations on the fluid (eqs. 5.5-5.8), gravity on every free
// particle, spring forces / mass on free body points; pinned points stay still. With several
// threads the whole evaluation is one parallel region: each thread unpacks and packs its own
// range of fluid particles, and the last one also does the solid particles and the body.
void CoupledSystem::compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const {
  evaluate(t, y, nullptr, dydt);
}

/// The Runge–Kutta stage state y + h Σ_j w_j k_j (eq. 2.38) on the Vec2 entries [first, last):
/// OdeSystem's sums restricted to that segment (the same operations in the same order).
struct CoupledSystem::StageSum {
  const ode::Vector* y;
  double h;
  std::span<const double> w;
  std::span<const ode::Vector> k;
  ode::Vector* out;
  void form(std::size_t first, std::size_t last) const {
    ode::form_stage_segment(*y, h, w, k, *out, static_cast<Eigen::Index>(2 * first),
                            static_cast<Eigen::Index>(2 * (last - first)));
  }
};

void CoupledSystem::compute_stage_derivative(double t, const ode::Vector& y, double h, std::span<const double> weights,
                                             std::span<const ode::Vector> k, ode::Vector& y_stage,
                                             ode::Vector& dydt) const {
  if (scene_.fluid_count == 0 || y.size() != dimension()) {
    OdeSystem::compute_stage_derivative(t, y, h, weights, k, y_stage, dydt);
    return;
  }
  y_stage.resize(y.size());
  const StageSum sum{&y, h, weights, k, &y_stage};
  evaluate(t, y_stage, &sum, dydt);
}

void CoupledSystem::evaluate(double t, const ode::Vector& y, const StageSum* sum, ode::Vector& dydt) const {
  const std::size_t n = scene_.position.size(), nf = scene_.fluid_count;
  if (y.size() != dimension()) throw std::invalid_argument("CoupledSystem: state size does not match the scene");
  dydt.resize(y.size());
  af_.resize(nf);
  if (nf == 0) {
    rest_derivative(t, y, dydt);
    return;
  }
  // One pointer per callback keeps each std::function within its small-object buffer (no allocation).
  struct Context {
    const CoupledSystem* self;
    const ode::Vector* y;
    ode::Vector* dydt;
    std::size_t half, fluid;
    double t;
    const StageSum* sum;
  } const c{this, &y, &dydt, n + scene_.body.points.size(), nf, t, sum};
  EvaluationHooks hooks;
  hooks.load = [p = &c](std::size_t b, std::size_t e, Vec2* x, Vec2* v) {
    if (p->sum != nullptr) {  // this part's positions and velocities of the stage state
      p->sum->form(b, e);
      p->sum->form(p->half + b, p->half + e);
    }
    for (std::size_t i = b; i < e; ++i) {
      x[i] = get(*p->y, i);
      v[i] = get(*p->y, p->half + i);
    }
  };
  hooks.store = [p = &c](std::size_t b, std::size_t e) {
    const CoupledSystem& s = *p->self;
    for (std::size_t i = b; i < e; ++i) {
      set(*p->dydt, i, get(*p->y, p->half + i));
      set(*p->dydt, p->half + i, s.af_[i] + s.scene_.particle_gravity);
    }
  };
  hooks.side = [p = &c] {
    if (p->sum != nullptr) {  // the solid particles and the body
      p->sum->form(p->fluid, p->half);
      p->sum->form(p->half + p->fluid, 2 * p->half);
    }
    p->self->rest_derivative(p->t, *p->y, *p->dydt);
  };
  fluid_->compute_accelerations(std::span<const double>(scene_.mass.data(), nf), af_, hooks);
}

// The part of y' that is not SPH: solid point masses (gravity only) and the body.
void CoupledSystem::rest_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const {
  const std::size_t n = scene_.position.size(), m = scene_.body.points.size(), half = n + m, nf = scene_.fluid_count;
  for (std::size_t i = nf; i < n; ++i) {
    set(dydt, i, get(y, half + i));
    set(dydt, half + i, scene_.particle_gravity);
  }
  if (m == 0) return;
  xb_.resize(m);
  vb_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    xb_[i] = get(y, n + i);
    vb_[i] = get(y, half + n + i);
  }
  if (scene_.muscles) scene_.muscles(t, body_);
  elastic::accumulate_forces(body_, xb_, vb_, t, fb_);
  for (std::size_t i = 0; i < m; ++i) {
    const bool free = is_free(body_, i);
    set(dydt, n + i, free ? vb_[i] : Vec2{});
    set(dydt, half + n + i, free ? fb_[i] / body_.points.mass[i] : Vec2{});
  }
}

namespace {

class StepDoublingOnly final : public ode::Integrator {
 public:
  explicit StepDoublingOnly(std::unique_ptr<ode::Integrator> inner) : inner_(std::move(inner)) {}
  std::string_view name() const override { return inner_->name(); }
  int order() const override { return inner_->order(); }
  ode::StepOutcome step(const ode::OdeSystem& system, double t, double dt, const ode::Vector& y, ode::Vector& y_out,
                        ode::Vector*) override {
    ode::StepOutcome o = inner_->step(system, t, dt, y, y_out, nullptr);
    o.has_error = false;
    return o;
  }
  void reset() override { inner_->reset(); }

 private:
  std::unique_ptr<ode::Integrator> inner_;
};

std::string diverged(double t, std::int64_t step, const std::string& what) {
  std::ostringstream s;
  s << "simulation diverged at t = " << t << " s (step " << step << "): " << what;
  return s.str();
}

/// Masses for collisions: pinned body points are infinitely heavy.
std::vector<double> body_masses(const elastic::Body& body) {
  std::vector<double> m(body.points.size());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = is_free(body, i) ? body.points.mass[i] : kInf;
  return m;
}

std::string check_speeds(const Scene& s, double limit) {
  for (std::size_t i = 0; i < s.velocity.size(); ++i) {
    if (!(norm(s.velocity[i]) <= limit)) return "particle " + std::to_string(i) + " moves faster than output.max_speed";
  }
  for (std::size_t i = 0; i < s.body.points.size(); ++i) {
    if (!(norm(s.body.points.velocity[i]) <= limit)) {
      return "body point " + std::to_string(i) + " moves faster than output.max_speed";
    }
  }
  return {};
}

/// The time loop: like sim::integrate, plus emission events, the eq. 5.31 step limit and the
/// collision pass after every accepted step.
class Runner {
 public:
  Runner(Scene& scene, const RunSettings& settings) : scene_(scene), settings_(settings), system_(scene) {
    body_mass_ = body_masses(scene.body);
    result_.boundary_width_m = scene.outline.size() > 0 ? boundary_width(scene.outline, scene.body.points.position) : kInf;
    make_stepper();
  }

  RunResult run(const SceneFrameCallback& on_frame, const sim::ProgressCallback& progress) {
    const sim::TimeSettings& ts = settings_.time;
    const double eps = 1e-9 * ts.frame_interval;
    ode::Vector y = system_.pack_state();
    double dt_next = ts.dt;
    std::int64_t emitted = 0;
    sim::FrameClock clock(ts.frame_interval, ts.duration, eps, sim::FrameClock::Ending::whole_frames);
    sim::ClockedRun loop;
    loop.time = [this] { return t_; };
    loop.frame = [&](std::int64_t) -> std::string {
      system_.unpack_state(y);
      std::string problem = sim::check_finite(y);
      if (problem.empty()) problem = check_speeds(scene_, settings_.max_speed);
      if (problem.empty()) problem = on_frame(t_, scene_, system_);
      return problem.empty() ? problem : diverged(t_, result_.statistics.steps, problem);
    };
    loop.after_frame_check = [&] {
      if (emitter_due(emitted, eps)) {
        emit(y);
        ++emitted;
      }
    };
    loop.step = [&](double frame_target) -> sim::StepResult {
      const double t_target = std::min(frame_target, next_emission(emitted));
      const double thin_limit = thin_boundary_limit(y);
      const bool to_target = thin_limit >= t_target - t_;
      const double dt_limit = std::min(t_target - t_, thin_limit);
      y_start_ = y;
      double dt_taken = 0.0;
      try {
        if (ts.adaptive) {
          dt_next = stepper_->step(system_, t_, y, dt_next, dt_limit, dt_taken);
        } else {
          dt_taken = std::min(ts.dt, dt_limit);
          if (!integrator_->step(system_, t_, dt_taken, y, y_next_, nullptr).ok) {
            return sim::StepResult::failed_with(
                diverged(t_, result_.statistics.steps, "the integrator could not complete a step"));
          }
          y.swap(y_next_);
          t_ += dt_taken;
        }
      } catch (const ode::StepSizeUnderflow& e) {
        return sim::StepResult::failed_with(diverged(t_, result_.statistics.steps, e.what()));
      }
      if (to_target && std::abs(t_ - t_target) <= eps) t_ = t_target;
      ++result_.statistics.steps;
      collide(y, dt_taken);
      if (std::string problem = sim::check_finite(y); !problem.empty())
        return sim::StepResult::failed_with(diverged(t_, result_.statistics.steps, problem));
      return {};
    };
    return finish(sim::run_frames(clock, loop, progress).failure);
  }

 private:
  void make_stepper() {
    if (stepper_) rejected_before_ += stepper_->statistics().rejected;
    integrator_ = ode::make_jacobian_free_integrator(settings_.time.integrator, settings_.newton);
    if (settings_.error_control == "step-doubling") integrator_ = without_embedded_pair(std::move(integrator_));
    stepper_ = std::make_unique<ode::AdaptiveStepper>(*integrator_, settings_.time.tolerances);
  }

  double next_emission(std::int64_t emitted) const {
    const Emitter& e = settings_.emitter;
    if (e.interval_s <= 0.0 || static_cast<std::size_t>(emitted) >= e.max_count) return kInf;
    return static_cast<double>(emitted) * e.interval_s;
  }
  bool emitter_due(std::int64_t emitted, double eps) const { return t_ >= next_emission(emitted) - eps; }

  /// Adds one fluid particle (after the existing fluid particles) and rebuilds the state.
  void emit(ode::Vector& y) {
    system_.unpack_state(y);
    const Emitter& e = settings_.emitter;
    const auto at = static_cast<std::ptrdiff_t>(scene_.fluid_count);
    scene_.position.insert(scene_.position.begin() + at, e.position);
    scene_.velocity.insert(scene_.velocity.begin() + at, e.velocity);
    scene_.mass.insert(scene_.mass.begin() + at, e.mass_kg);
    ++scene_.fluid_count;
    y = system_.pack_state();
    make_stepper();
  }

  /// Eq. 5.31: Δt < w_b / (2 |v_max|), with v_max the largest particle speed plus the largest
  /// body-point speed (a bound on their relative speed).
  double thin_boundary_limit(const ode::Vector& y) const {
    if (!settings_.thin_boundary_limit || !std::isfinite(result_.boundary_width_m)) return kInf;
    const std::size_t n = scene_.position.size(), m = scene_.body.points.size(), half = n + m;
    const double v = fastest_speed(y, half, n) + fastest_speed(y, half + n, m);
    return v > 0.0 ? result_.boundary_width_m / (2.0 * v) : kInf;
  }

  /// Largest |v| of `count` velocities from slot `first` of y: picked by |v|², so only one hypot.
  static double fastest_speed(const ode::Vector& y, std::size_t first, std::size_t count) {
    double best = -1.0;
    std::size_t at = first;
    for (std::size_t i = first; i < first + count; ++i) {
      const double s = norm_squared(get(y, i));
      if (s > best) {
        best = s;
        at = i;
      }
    }
    return count > 0 ? norm(get(y, at)) : 0.0;
  }

  void collide(ode::Vector& y, double dt) {
    const std::size_t n = scene_.position.size(), m = scene_.body.points.size(), half = n + m;
    x0_.resize(n); x1_.resize(n); v1_.resize(n);
    b0_.resize(m); b1_.resize(m); bv_.resize(m);
    for (std::size_t i = 0; i < n; ++i) { x0_[i] = get(y_start_, i); x1_[i] = get(y, i); v1_[i] = get(y, half + i); }
    for (std::size_t i = 0; i < m; ++i) { b0_[i] = get(y_start_, n + i); b1_[i] = get(y, n + i); bv_[i] = get(y, half + n + i); }
    const MovingPoints particles{&x0_, &x1_, &v1_, &scene_.mass};
    const MovingPoints body{&b0_, &b1_, &bv_, &body_mass_};
    const CollisionStatistics s = handler_.handle(particles, m > 0 ? body : MovingPoints{}, scene_.outline, scene_.walls, dt);
    if (s.edge_collisions + s.wall_collisions == 0) return;
    result_.collisions += s;
    // Only what changed: every write here pulls the entry's cache line to this thread's core.
    for (std::size_t i = 0; i < n; ++i) {
      if (x1_[i] != get(y, i)) set(y, i, x1_[i]);
      if (v1_[i] != get(y, half + i)) set(y, half + i, v1_[i]);
    }
    for (std::size_t i = 0; i < m; ++i) { set(y, n + i, b1_[i]); set(y, half + n + i, bv_[i]); }
  }

  RunResult finish(std::string failure) {
    result_.statistics.simulated_seconds = t_;
    result_.statistics.function_evaluations = system_.evaluations();
    result_.threads = system_.fluid().threads();
    result_.parallel_evaluations = system_.fluid().parallel_evaluations();
    result_.list_rebuilds = system_.fluid().list_rebuilds();
    result_.statistics.rejected_steps = rejected_before_ + stepper_->statistics().rejected;
    result_.failed = !failure.empty();
    result_.failure = std::move(failure);
    return result_;
  }

  Scene& scene_;
  const RunSettings& settings_;
  CoupledSystem system_;
  CollisionHandler handler_{scene_.collision};
  std::unique_ptr<ode::Integrator> integrator_;
  std::unique_ptr<ode::AdaptiveStepper> stepper_;
  std::int64_t rejected_before_ = 0;
  std::vector<double> body_mass_;
  RunResult result_;
  double t_ = 0.0;
  ode::Vector y_start_, y_next_;
  std::vector<Vec2> x0_, x1_, v1_, b0_, b1_, bv_;
};

}  // namespace

std::unique_ptr<ode::Integrator> without_embedded_pair(std::unique_ptr<ode::Integrator> inner) {
  return std::make_unique<StepDoublingOnly>(std::move(inner));
}

RunResult run(Scene& scene, const RunSettings& settings, const SceneFrameCallback& on_frame,
              const sim::ProgressCallback& progress) {
  Runner runner(scene, settings);
  return runner.run(on_frame, progress);
}

double kinetic_energy(const Scene& s) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.velocity.size(); ++i) e += 0.5 * s.mass[i] * norm_squared(s.velocity[i]);
  for (std::size_t i = 0; i < s.body.points.size(); ++i) {
    if (is_free(s.body, i)) e += 0.5 * s.body.points.mass[i] * norm_squared(s.body.points.velocity[i]);
  }
  return e;
}

Vec2 momentum(const Scene& s) {
  Vec2 p{};
  for (std::size_t i = 0; i < s.velocity.size(); ++i) p += s.velocity[i] * s.mass[i];
  for (std::size_t i = 0; i < s.body.points.size(); ++i) {
    if (is_free(s.body, i)) p += s.body.points.velocity[i] * s.body.points.mass[i];
  }
  return p;
}

}  // namespace jellysim::sph
