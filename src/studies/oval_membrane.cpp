#include "jellysim/studies/oval_membrane.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "jellysim/sim/frame_clock.hpp"

namespace jellysim::studies {

namespace {

/// Perimeter of an ellipse (Ramanujan's second approximation).
double ellipse_perimeter(double a, double b) {
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return std::numbers::pi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

}  // namespace

elastic::Body make_oval_membrane(const OvalMembraneSettings& s) {
  const double dx = s.box_m / s.cells;
  const double perimeter = ellipse_perimeter(s.semi_axis_x_m, s.semi_axis_y_m);
  const int n = std::max(8, static_cast<int>(std::ceil(perimeter / (s.spacing_fraction * dx))));
  const Vec2 centre{0.5 * s.box_m, 0.5 * s.box_m};
  elastic::Body body;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    body.add_point(centre + Vec2{s.semi_axis_x_m * std::cos(a), s.semi_axis_y_m * std::sin(a)}, 1.0);
  }
  for (int k = 0; k < n; ++k) body.add_linear_spring(k, (k + 1) % n, s.stiffness, 0.0);
  return body;
}

double polygon_area(const std::vector<Vec2>& ring) {
  double twice = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) twice += cross(ring[k], ring[(k + 1) % ring.size()]);
  return 0.5 * twice;
}

double ring_aspect_ratio(const std::vector<Vec2>& ring) {
  Vec2 c{};
  for (Vec2 p : ring) c += p;
  c = c / static_cast<double>(ring.size());
  double lo = INFINITY, hi = 0.0;
  for (Vec2 p : ring) {
    lo = std::min(lo, norm(p - c));
    hi = std::max(hi, norm(p - c));
  }
  return hi / lo;
}

namespace {

/// The membrane's frame clock counts steps: the study steps by a fixed dt_s, so a frame is due every
/// round(frame_interval / dt) steps and at the last of round(duration / dt) steps (half a step of
/// tolerance: step counts are whole numbers).
sim::FrameClock step_clock(const OvalMembraneSettings& s) {
  const double total_steps = static_cast<double>(std::lround(s.duration_s / s.dt_s));
  const double steps_per_frame = static_cast<double>(std::max(1L, std::lround(s.frame_interval_s / s.dt_s)));
  return sim::FrameClock(steps_per_frame, total_steps, 0.5, sim::FrameClock::Ending::at_duration);
}

}  // namespace

MembraneRun run_oval_membrane(const OvalMembraneSettings& s,
                              const std::function<void(const MembraneFrame&)>& on_frame) {
  const auto start = std::chrono::steady_clock::now();
  const fluid::MacGrid grid(s.cells, s.cells, s.box_m, s.box_m);
  fluid::FluidSettings fs;
  fs.viscosity_m2_per_s = s.viscosity_m2_per_s;
  fs.density_kg_per_m3 = s.density_kg_per_m3;
  fs.boundaries = fluid::Boundaries::all(fluid::BoundaryType::no_slip);
  fs.pressure_solver = s.pressure_solver;
  fs.safety_factor = 1.0;
  auto fluid = fluid::make_fluid_solver(s.solver, grid, fs);
  elastic::Body body = make_oval_membrane(s);
  coupling::ImmersedBoundary ib(*fluid, body, s.coupling);
  MembraneRun run;
  const coupling::StabilityLimits limits{};
  long steps = 0;
  sim::ClockedRun loop;
  loop.time = [&] { return static_cast<double>(steps); };
  loop.step = [&](double) -> sim::StepResult {
    ib.step(s.dt_s);
    ++steps;
    if (std::string problem = coupling::check_stability(fluid->state(), body, limits); !problem.empty())
      return sim::StepResult::failed_with(problem + " at t = " + std::to_string(ib.time_s()) + " s (step " +
                                          std::to_string(steps) + ")");
    return {};
  };
  loop.frame = [&](std::int64_t) -> std::string {
    MembraneFrame f{ib.time_s(), polygon_area(body.points.position), ring_aspect_ratio(body.points.position),
                    body.points.position};
    if (on_frame) on_frame(f);
    run.frames.push_back(std::move(f));
    return {};
  };
  sim::FrameClock clock = step_clock(s);
  run.failure = sim::run_frames(clock, loop).failure;
  run.steps = ib.steps();
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace jellysim::studies
