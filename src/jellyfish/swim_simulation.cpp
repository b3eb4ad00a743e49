#include "jellysim/jellyfish/swim_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "jellysim/elastic/mirror.hpp"
#include "jellysim/fluid/mirror.hpp"

namespace jellysim::jellyfish {

namespace {

std::string when(double t, long step) {
  std::ostringstream s;
  s.precision(6);
  s << " at t = " << t << " s (step " << step << ")";
  return s.str();
}

std::string format_length(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v << " m";
  return s.str();
}

/// Appends `part` to `whole`, shifting its point indices.
void append_body(const elastic::Body& part, elastic::Body& whole) {
  const int offset = static_cast<int>(whole.points.size());
  for (std::size_t p = 0; p < part.points.size(); ++p)
    whole.add_point(part.points.position[p], part.points.mass[p] > 0 ? part.points.mass[p] : 1e-6);
  for (std::size_t s = 0; s < part.linear.size(); ++s)
    whole.add_linear_spring(part.linear.i[s] + offset, part.linear.j[s] + offset, part.linear.stiffness[s],
                            part.linear.rest_length[s]);
  for (std::size_t s = 0; s < part.angular.size(); ++s)
    whole.add_angular_spring(part.angular.i[s] + offset, part.angular.j[s] + offset, part.angular.k[s] + offset,
                             part.angular.stiffness[s], part.angular.rest_angle[s]);
}

/// The outline a jellyfish occupies at the start: its umbrella closed across the aperture, with
/// the tentacles' extent, as a polygon (for overlap and containment checks).
std::vector<Vec2> jellyfish_outline(const Jellyfish& j) {
  std::vector<Vec2> p = j.umbrella_points();
  return p;
}

/// The jellyfish whose points start at first_point[j] and end before first_point[j + 1].
std::size_t owner_of_point(const std::vector<int>& first_point, int p) {
  const auto it = std::upper_bound(first_point.begin(), first_point.end(), p);
  return static_cast<std::size_t>(it - first_point.begin()) - 1;
}

bool same_contraction(const JellyfishSpec& a, const JellyfishSpec& b) {
  return a.frequency_hz == b.frequency_hz && a.gamma == b.gamma && a.phase_cycles == b.phase_cycles &&
         a.profile.shape == b.profile.shape && a.profile.contract_fraction == b.profile.contract_fraction &&
         a.profile.expansion_exponent == b.profile.expansion_exponent &&
         a.profile.trochoid_skew == b.profile.trochoid_skew &&
         a.aperture_expansion_exponent == b.aperture_expansion_exponent && a.neural_delay_s == b.neural_delay_s &&
         a.closed_loop == b.closed_loop && a.controller_alpha == b.controller_alpha;
}

/// What in the specs (walls, current, steering, obstacle paths) breaks the mirror symmetry.
std::string mirror_spec_problem(const SwimSettings& s) {
  const fluid::Boundaries& b = s.tank.boundaries;
  if (b.west.type != b.east.type) return "the west and east sides are of different types";
  if (b.west.velocity_m_per_s != Vec2{-b.east.velocity_m_per_s.x, b.east.velocity_m_per_s.y})
    return "the west and east wall or in-flow velocities are not mirror images";
  if (b.south.velocity_m_per_s.x != 0.0 || b.north.velocity_m_per_s.x != 0.0)
    return "the south or north wall moves sideways";
  if (s.tank.current_m_per_s.x != 0.0) return "the current has a sideways component";
  for (std::size_t j = 0; j < s.school.size(); ++j)
    if (s.school[j].steering) return "jellyfish " + std::to_string(j + 1) + " steers";
  for (const ObstacleSpec& o : s.obstacles)
    if (o.motion.velocity_m_per_s.x != 0.0 || o.motion.amplitude_m.x != 0.0) return o.name + " moves sideways";
  return {};
}

/// What in the assembled body (points, springs, contraction) breaks the mirror symmetry; on
/// success fills the point and jellyfish partners.
std::string mirror_body_problem(const SwimSettings& s, const elastic::Body& body, const std::vector<int>& first_point,
                                std::vector<int>& partners, std::vector<int>& jellyfish_partners) {
  const double axis = 0.5 * s.tank.width_m;
  partners = elastic::mirror_partners(body, axis, 1e-9 * std::max(s.tank.width_m, s.tank.height_m));
  if (partners.empty())
    return "the bodies are not mirror images of each other about x = " + std::to_string(axis) +
           " m (a jellyfish off the centre line or tilted, or an obstacle without a mirror image)";
  jellyfish_partners.assign(s.school.size(), 0);
  for (std::size_t j = 0; j < s.school.size(); ++j) {
    const std::size_t k = owner_of_point(first_point, partners[static_cast<std::size_t>(first_point[j])]);
    if (!same_contraction(s.school[j], s.school[k]))
      return "jellyfish " + std::to_string(j + 1) + " and its mirror image, jellyfish " + std::to_string(k + 1) +
             ", contract differently";
    jellyfish_partners[j] = static_cast<int>(k);
  }
  if (!elastic::springs_mirror_symmetric(body, partners)) return "the springs are not mirror images of each other";
  return {};
}

}  // namespace

std::string mirror_symmetry_problem(const SwimSettings& settings) {
  if (std::string problem = mirror_spec_problem(settings); !problem.empty()) return problem;
  elastic::Body body;
  std::vector<int> first_point;
  for (const JellyfishSpec& spec : settings.school) {
    first_point.push_back(static_cast<int>(body.points.size()));
    append_body(Jellyfish(spec).body(), body);
  }
  for (const ObstacleSpec& o : settings.obstacles) add_obstacle(o, peskin_spacing(settings.tank), body);
  std::vector<int> partners, jellyfish_partners;
  return mirror_body_problem(settings, body, first_point, partners, jellyfish_partners);
}

const JellyfishSpec& SwimSettings::jellyfish() const {
  if (school.empty()) throw std::logic_error("the scene has no jellyfish");
  return school.front();
}

double peskin_spacing(const TankSpec& tank) {
  return 0.5 * std::min(tank.width_m / tank.cells_x, tank.height_m / tank.cells_y);
}

void validate_layout(const SwimSettings& settings) {
  const TankSpec& t = settings.tank;
  struct Shape {
    std::string name;
    std::vector<Vec2> polygon;  ///< closed outline
    std::vector<Vec2> points;   ///< every point that must lie inside the tank
  };
  std::vector<Shape> shapes;
  for (std::size_t k = 0; k < settings.school.size(); ++k) {
    const Jellyfish j(settings.school[k]);
    Shape s{"jellyfish " + std::to_string(k + 1), jellyfish_outline(j), j.body().points.position};
    shapes.push_back(std::move(s));
  }
  for (const ObstacleSpec& o : settings.obstacles) {
    validate(o);
    std::vector<Vec2> outline = obstacle_outline(o);
    shapes.push_back({o.name, outline, outline});
  }
  const double margin = 0.5 * std::min(t.width_m / t.cells_x, t.height_m / t.cells_y);
  for (const Shape& s : shapes)
    for (Vec2 p : s.points)
      if (!(p.x >= margin && p.x <= t.width_m - margin && p.y >= margin && p.y <= t.height_m - margin))
        throw std::invalid_argument(s.name + " reaches outside the tank: point (" + std::to_string(p.x) + ", " +
                                    std::to_string(p.y) + ") m is not inside [" + std::to_string(margin) + ", " +
                                    std::to_string(t.width_m - margin) + "] x [" + std::to_string(margin) + ", " +
                                    std::to_string(t.height_m - margin) + "] m (half a cell from the walls)");
  for (std::size_t a = 0; a < shapes.size(); ++a)
    for (std::size_t b = a + 1; b < shapes.size(); ++b)
      if (polygons_overlap(shapes[a].polygon, shapes[b].polygon))
        throw std::invalid_argument(shapes[a].name + " and " + shapes[b].name + " overlap; move them apart");
}

SwimSimulation::SwimSimulation(const SwimSettings& settings) : settings_(settings) {
  const TankSpec& t = settings_.tank;
  for (const JellyfishSpec& spec : settings_.school) {
    school_.push_back(std::make_unique<Jellyfish>(spec));
    jellyfish_offset_.push_back(static_cast<int>(body_.points.size()));
    jellyfish_spring_offset_.push_back(static_cast<int>(body_.linear.size()));
    jellyfish_joint_offset_.push_back(static_cast<int>(body_.angular.size()));
    append_body(school_.back()->body(), body_);
  }
  strain_reference_ = body_.linear.rest_length;
  for (std::size_t j = 0; j < school_.size(); ++j) {
    const JellyfishLayout& layout = school_[j]->layout();
    for (std::size_t k = 0; k < layout.muscle_springs.size(); ++k)
      strain_reference_[static_cast<std::size_t>(jellyfish_spring_offset_[j] + layout.muscle_springs[k])] =
          layout.muscle_uncontracted_m[k];
  }
  const double spacing = peskin_spacing(t);
  for (const ObstacleSpec& o : settings_.obstacles) {
    validate(o);
    obstacles_.push_back(add_obstacle(o, spacing, body_));
  }
  strain_reference_.resize(body_.linear.size(), 0.0);  // tethers have zero rest length: no strain

  set_up_mirror_symmetry();
  half_tank_ = mirror_active_ && t.half_tank && t.cells_x % 2 == 0;
  fluid_ = make_fluid(half_tank_);
  coupling_ = make_coupling(half_tank_);
  if (t.tracers_per_side > 0) {
    const double margin_x = 0.5 * t.width_m / t.tracers_per_side, margin_y = 0.5 * t.height_m / t.tracers_per_side;
    tracers_ = fluid::Tracers::lattice({margin_x, margin_y}, {t.width_m - margin_x, t.height_m - margin_y},
                                       t.tracers_per_side, t.tracers_per_side);
  }
}

std::unique_ptr<fluid::FluidSolver> SwimSimulation::make_fluid(bool east_half) const {
  const TankSpec& t = settings_.tank;
  const fluid::MacGrid whole(t.cells_x, t.cells_y, t.width_m, t.height_m);
  fluid::FluidSettings fs;
  fs.viscosity_m2_per_s = fluid_ ? fluid_->settings().viscosity_m2_per_s : t.viscosity_m2_per_s;  // live edits stay
  fs.density_kg_per_m3 = t.density_kg_per_m3;
  fs.boundaries = t.boundaries;
  if (east_half) {
    // The centre line is a symmetry plane: free slip (u = 0, v and p even). A periodic tank's
    // seam is one too.
    fs.boundaries.west = {fluid::BoundaryType::free_slip, {}};
    if (t.boundaries.periodic_x()) fs.boundaries.east = {fluid::BoundaryType::free_slip, {}};
  }
  fs.pressure_solver = t.pressure_solver;
  fs.pressure.relative_tolerance = t.pressure_tolerance;
  fs.diffusion_tolerance = std::min(fs.diffusion_tolerance, t.pressure_tolerance);
  fs.safety_factor = 1.0;  // the coupling chooses Δt; the Eulerian solver only guards it
  auto fluid = fluid::make_fluid_solver(t.solver, east_half ? fluid::east_half(whole) : whole, fs);
  if (t.current_m_per_s.x != 0.0 || t.current_m_per_s.y != 0.0) {
    fluid->state().velocity.u.fill(t.current_m_per_s.x);
    fluid->state().velocity.v.fill(t.current_m_per_s.y);
    fluid->apply_boundaries();
  }
  return fluid;
}

std::unique_ptr<coupling::ImmersedBoundary> SwimSimulation::make_coupling(bool east_half) {
  coupling::CouplingSettings c = settings_.coupling;
  c.west_mirror = east_half;
  auto coupling = std::make_unique<coupling::ImmersedBoundary>(*fluid_, body_, c,
                                                              [this](double time, elastic::Body&) { actuate(time); });
  if (mirror_active_) coupling->set_mirror_symmetry(mirror_partner_);
  return coupling;
}

void SwimSimulation::leave_half_tank() {
  if (!half_tank_) return;
  fluid::FlowState whole;
  fluid::unfold_east_half(fluid_->state(), whole, settings_.tank.boundaries);
  std::unique_ptr<fluid::FluidSolver> fluid = make_fluid(false);
  fluid->state().velocity = whole.velocity;
  fluid->state().pressure = whole.pressure;
  fluid->set_time_s(fluid_->time_s());
  std::unique_ptr<coupling::ImmersedBoundary> previous = std::move(coupling_);
  fluid_ = std::move(fluid);  // the previous coupling refers to the old fluid: keep it alive until here
  half_tank_ = false;
  coupling_ = make_coupling(false);
  coupling_->continue_from(*previous);
}

const fluid::FlowState& SwimSimulation::flow() const {
  if (!half_tank_) return fluid_->state();
  if (unfolded_step_ != steps()) {
    fluid::unfold_east_half(fluid_->state(), unfolded_, settings_.tank.boundaries);
    unfolded_step_ = steps();
  }
  return unfolded_;
}

SwimSimulation::~SwimSimulation() = default;

const Jellyfish& SwimSimulation::jellyfish(std::size_t i) const {
  if (i >= school_.size()) throw std::out_of_range("no jellyfish " + std::to_string(i) + " in the scene");
  return *school_[i];
}

void SwimSimulation::actuate(double t) {
  // Each jellyfish sets its muscles (and steering joints) on its own body; the coupled body takes
  // over the rest lengths, rest angles and spring constants.
  for (std::size_t j = 0; j < school_.size(); ++j) {
    school_[j]->actuate(t);
    const elastic::Body& part = school_[j]->body();
    const auto ls = static_cast<std::size_t>(jellyfish_spring_offset_[j]);
    const auto as = static_cast<std::size_t>(jellyfish_joint_offset_[j]);
    std::copy(part.linear.rest_length.begin(), part.linear.rest_length.end(), body_.linear.rest_length.begin() + static_cast<std::ptrdiff_t>(ls));
    std::copy(part.linear.stiffness.begin(), part.linear.stiffness.end(), body_.linear.stiffness.begin() + static_cast<std::ptrdiff_t>(ls));
    std::copy(part.angular.rest_angle.begin(), part.angular.rest_angle.end(), body_.angular.rest_angle.begin() + static_cast<std::ptrdiff_t>(as));
    std::copy(part.angular.stiffness.begin(), part.angular.stiffness.end(), body_.angular.stiffness.begin() + static_cast<std::ptrdiff_t>(as));
  }
}

void SwimSimulation::set_up_mirror_symmetry() {
  if (settings_.tank.symmetry == MirrorSymmetry::none) return;
  std::string problem = mirror_spec_problem(settings_);
  if (problem.empty())
    problem = mirror_body_problem(settings_, body_, jellyfish_offset_, mirror_partner_, jellyfish_mirror_);
  if (!problem.empty()) {
    if (settings_.tank.symmetry == MirrorSymmetry::mirror)
      throw std::invalid_argument("tank.symmetry = \"mirror\" needs a scene that is its own mirror image: " + problem);
    mirror_note_ = "the scene is not its own mirror image: " + problem;
    return;
  }
  mirror_active_ = true;
}

void SwimSimulation::keep_mirror_symmetry() {
  if (!half_tank_) fluid::keep_mirror_symmetric_part(fluid_->state());  // the half tank is symmetric by construction
  elastic::keep_mirror_symmetric_part(body_, mirror_partner_, 0.5 * settings_.tank.width_m);
}

void SwimSimulation::end_mirror_symmetry(const std::string& why) {
  if (!mirror_active_) return;
  mirror_active_ = false;
  leave_half_tank();
  coupling_->set_mirror_symmetry({});
  std::ostringstream note;
  note.precision(4);
  note << "ended at t = " << time_s() << " s: " << why;
  mirror_note_ = note.str();
}

void SwimSimulation::edit_of_jellyfish(std::size_t j, const char* what) {
  if (mirror_active_ && jellyfish_mirror_.at(j) != static_cast<int>(j))
    end_mirror_symmetry(std::string(what) + " of jellyfish " + std::to_string(j + 1) + " alone");
}

void SwimSimulation::copy_back_to_jellyfish() {
  for (std::size_t j = 0; j < school_.size(); ++j) {
    elastic::Body& part = school_[j]->body();
    const auto first = static_cast<std::ptrdiff_t>(jellyfish_offset_[j]);
    const auto count = static_cast<std::ptrdiff_t>(part.points.size());
    std::copy(body_.points.position.begin() + first, body_.points.position.begin() + first + count, part.points.position.begin());
    std::copy(body_.points.velocity.begin() + first, body_.points.velocity.begin() + first + count, part.points.velocity.begin());
  }
}

std::vector<Vec2> SwimSimulation::obstacle_outline(std::size_t i) const {
  std::vector<Vec2> p;
  for (int m : obstacles_.at(i).markers) p.push_back(body_.points.position[static_cast<std::size_t>(m)]);
  return p;
}

Vec2 SwimSimulation::obstacle_force(std::size_t i) const { return obstacle_fluid_force(obstacles_.at(i), body_); }

double SwimSimulation::obstacle_leakage(std::size_t i) const {
  const ObstacleParts& parts = obstacles_.at(i);
  const fluid::Velocity& u = flow().velocity;
  const auto& x = body_.points.position;
  const auto& v = body_.points.velocity;
  double crossing = 0.0;
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    const auto a = static_cast<std::size_t>(parts.markers[k]);
    const auto b = static_cast<std::size_t>(parts.markers[(k + 1) % parts.markers.size()]);
    const Vec2 mid = 0.5 * (x[a] + x[b]);
    const Vec2 wall_velocity = 0.5 * (v[a] + v[b]);
    const Vec2 normal_times_length{x[b].y - x[a].y, x[a].x - x[b].x};  // outward for a counter-clockwise outline
    const Vec2 relative = Vec2{u.u.sample(mid), u.v.sample(mid)} - wall_velocity;
    crossing += std::abs(dot(relative, normal_times_length));
  }
  return 0.5 * crossing;
}

std::string SwimSimulation::check() const {
  std::string problem = coupling::check_stability(fluid_->state(), body_, settings_.limits, &strain_reference_);
  if (!problem.empty()) return problem;
  for (std::size_t j = 0; j < school_.size(); ++j)
    if (polyline_self_intersects(school_[j]->umbrella_points()))
      return "structural instability: the umbrella of jellyfish " + std::to_string(j + 1) +
             " crossed itself (mesh inversion)";
  const double limit = settings_.obstacle_max_displacement_m > 0 ? settings_.obstacle_max_displacement_m
                                                                 : 2.0 * peskin_spacing(settings_.tank);
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    const ObstacleParts& parts = obstacles_[o];
    for (std::size_t k = 0; k < parts.markers.size(); ++k) {
      const Vec2 x = body_.points.position[static_cast<std::size_t>(parts.markers[k])];
      const double stretch = norm(x - body_.points.position[static_cast<std::size_t>(parts.targets[k])]);
      if (!(stretch <= limit))
        return "structural instability: " + settings_.obstacles[o].name + " was pushed " + format_length(stretch) +
               " off its place near (" + std::to_string(x.x) + ", " + std::to_string(x.y) +
               ") m, more than " + format_length(limit) + " (raise its stiffness)";
    }
  }
  return {};
}

SwimStep SwimSimulation::step(double max_dt_s) { return advance(std::min(coupling_->next_time_step(), max_dt_s)); }

SwimStep SwimSimulation::advance(double dt_s) {
  SwimStep s;
  s.dt_s = dt_s;
  if (!(s.dt_s >= settings_.coupling.min_time_step_s)) {
    s.failure = "numerical instability: the stable time step fell to " + std::to_string(s.dt_s) +
                " s, below min_time_step" + when(time_s(), coupling_->steps());
    return s;
  }
  const coupling::CoupledStepReport r = coupling_->step(s.dt_s);
  if (mirror_active_) keep_mirror_symmetry();
  copy_back_to_jellyfish();
  s.krylov_iterations = r.krylov.iterations;
  if (!tracers_.positions().empty()) tracers_.advect(flow().velocity, settings_.tank.boundaries, s.dt_s);
  if (std::string problem = check(); !problem.empty()) s.failure = problem + when(time_s(), coupling_->steps());
  return s;
}

SwimRunStats SwimSimulation::run(const FrameCallback& on_frame, const sim::ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  SwimRunStats stats;
  stats.smallest_step_s = INFINITY;
  const double duration = settings_.duration_s;
  sim::FrameClock clock(settings_.frame_interval_s, duration, 1e-12 * std::max(1.0, duration),
                        sim::FrameClock::Ending::nearest_frame);
  sim::ClockedRun loop;
  loop.time = [this] { return time_s(); };
  loop.frame = [&](std::int64_t) { return on_frame ? on_frame(*this) : std::string(); };
  loop.step = [&](double frame_time) -> sim::StepResult {
    // Land on the frame time without a sliver step before it.
    const double remaining = frame_time - time_s();
    const double natural = coupling_->next_time_step();
    const double limit = natural >= remaining ? remaining : (natural > 0.5 * remaining ? 0.5 * remaining : natural);
    const SwimStep s = advance(limit);
    if (s.failure.empty() || s.dt_s >= settings_.coupling.min_time_step_s) {
      stats.smallest_step_s = std::min(stats.smallest_step_s, s.dt_s);
      stats.largest_step_s = std::max(stats.largest_step_s, s.dt_s);
      stats.krylov_iterations += s.krylov_iterations;
    }
    if (!s.failure.empty()) {
      if (on_frame && s.dt_s >= settings_.coupling.min_time_step_s) on_frame(*this);  // keep the state that failed
      return sim::StepResult::failed_with(s.failure);
    }
    return {};
  };
  // Progress counts the coupling's steps (also those taken before run(), e.g. by the viewer).
  const sim::ProgressCallback steps_progress =
      progress ? sim::ProgressCallback([&](double t, double d, std::int64_t) { progress(t, d, coupling_->steps()); })
               : sim::ProgressCallback();
  stats.failure = sim::run_frames(clock, loop, steps_progress).failure;
  stats.simulated_seconds = time_s();
  stats.steps = coupling_->steps();
  stats.mirror_symmetric = mirror_active_;
  stats.half_tank = half_tank_;
  stats.symmetry_note = mirror_note_;
  stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!std::isfinite(stats.smallest_step_s)) stats.smallest_step_s = 0.0;
  return stats;
}

// ---- Live edits ----

void SwimSimulation::set_frequency(std::size_t j, double hz) {
  school_.at(j)->set_frequency(hz, time_s());
  edit_of_jellyfish(j, "a frequency change");
}
void SwimSimulation::set_gamma(std::size_t j, double gamma) {
  school_.at(j)->set_gamma(gamma);
  edit_of_jellyfish(j, "a contraction change");
}
void SwimSimulation::set_stiffness_scale(std::size_t j, double scale) {
  school_.at(j)->set_stiffness_scale(scale);
  edit_of_jellyfish(j, "a stiffness change");
}
void SwimSimulation::set_steer_target(std::size_t j, std::optional<Vec2> target_m) {
  school_.at(j)->set_steer_target(target_m);
  if (target_m) end_mirror_symmetry("jellyfish " + std::to_string(j + 1) + " began to steer");
}
void SwimSimulation::set_viscosity(double nu_m2_per_s) { fluid_->set_viscosity(nu_m2_per_s); }

void SwimSimulation::stir(Vec2 at_m, Vec2 delta_velocity_m_per_s, double radius_m) {
  if (!(radius_m > 0)) throw std::invalid_argument("stir radius must be > 0");
  auto splat = [&](fluid::Field& f, double amount) {
    for (int j = 0; j < f.count_y(); ++j)
      for (int i = 0; i < f.count_x(); ++i) {
        const double r2 = norm_squared(f.position(i, j) - at_m) / (radius_m * radius_m);
        if (r2 < 9.0) f(i, j) += amount * std::exp(-r2);
      }
  };
  end_mirror_symmetry("the fluid was stirred");
  splat(fluid_->state().velocity.u, delta_velocity_m_per_s.x);
  splat(fluid_->state().velocity.v, delta_velocity_m_per_s.y);
  fluid_->apply_boundaries();
}

void SwimSimulation::move_jellyfish(std::size_t j, Vec2 delta_m) {
  if (delta_m.x != 0.0 || jellyfish_mirror_.empty() || jellyfish_mirror_.at(j) != static_cast<int>(j))
    end_mirror_symmetry("jellyfish " + std::to_string(j + 1) + " was moved");
  elastic::Body& part = school_.at(j)->body();
  for (std::size_t p = 0; p < part.points.size(); ++p) {
    part.points.position[p] += delta_m;
    body_.points.position[static_cast<std::size_t>(jellyfish_offset_[j]) + p] += delta_m;
  }
}

void SwimSimulation::move_obstacle(std::size_t o, Vec2 delta_m) {
  ObstacleParts& parts = obstacles_.at(o);
  end_mirror_symmetry(settings_.obstacles.at(o).name + " was moved");
  *parts.shift += delta_m;
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    body_.points.position[static_cast<std::size_t>(parts.markers[k])] += delta_m;
    body_.points.position[static_cast<std::size_t>(parts.targets[k])] += delta_m;
  }
}

}  // namespace jellysim::jellyfish
