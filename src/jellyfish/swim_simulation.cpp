#include "jellysim/jellyfish/swim_simulation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/elastic/body_mirror.hpp"

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
         a.profile.pause_fraction == b.profile.pause_fraction &&
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
    Jellyfish(spec).move_into(body);
  }
  for (const ObstacleSpec& o : settings.obstacles) add_obstacle(o, coupling::peskin_spacing(settings.tank), body);
  for (const Ib2dObjectSpec& st : settings.structures) add_ib2d_object(st, coupling::peskin_spacing(settings.tank), body);
  std::vector<int> partners, jellyfish_partners;
  return mirror_body_problem(settings, body, first_point, partners, jellyfish_partners);
}

sim::FrameClock SwimSettings::frame_clock(double duration) const {
  const double tolerance = 1e-12 * std::max(1.0, duration);
  return frames_per_second > 0.0
             ? sim::FrameClock::at_rate(frames_per_second, duration, tolerance, sim::FrameClock::Ending::nearest_frame)
             : sim::FrameClock(frame_interval_s, duration, tolerance, sim::FrameClock::Ending::nearest_frame);
}

const JellyfishSpec& SwimSettings::jellyfish() const {
  if (school.empty()) throw std::logic_error("the scene has no jellyfish");
  return school.front();
}

MemoryEstimate estimate_memory(const SwimSettings& settings) {
  const coupling::TankSpec& t = settings.tank;
  MemoryEstimate e;
  e.cells = static_cast<double>(t.cells_x) * static_cast<double>(t.cells_y);
  const double spacing = coupling::peskin_spacing(t);
  for (const JellyfishSpec& j : settings.school) e.markers += plan_markers(j).markers;
  for (const ObstacleSpec& o : settings.obstacles) {
    const std::vector<Vec2> outline = obstacle_outline(o);
    double perimeter = 0.0;
    for (std::size_t k = 0; k < outline.size(); ++k) perimeter += norm(outline[(k + 1) % outline.size()] - outline[k]);
    e.markers += 2.0 * (perimeter / spacing + static_cast<double>(outline.size()));  // markers and their targets
  }
  for (const Ib2dObjectSpec& st : settings.structures)
    e.markers += 2.0 * static_cast<double>(st.structure.vertices.size());  // targets add an anchor each, at most
  e.frames = std::floor(settings.duration_s / settings.frame_interval_s) + 1.0;
  // Measured (docs/jellyfish.md, "Memory"): 25 MB base; 450 B per cell on the whole tank; the
  // marker-space solve's R, M and LU, 26 B per entry of a 2N × 2N matrix (plain GMRES keeps a
  // Krylov basis instead); the recorded frames' slices and metrics. Rounded up.
  const double unknowns = 2.0 * e.markers;
  const double dense = settings.coupling.preconditioner == coupling::Preconditioner::mobility
                           ? 32.0 * unknowns * unknowns
                           : 8.0 * unknowns * (settings.coupling.krylov_max_iterations + 2.0);
  const double per_frame = 64.0 * e.markers + 512.0;
  e.bytes = 32e6 + 600.0 * e.cells + 4096.0 * e.markers + dense + per_frame * e.frames;
  std::ostringstream b;
  b.precision(3);
  b << e.cells << " fluid cells, " << e.markers << " markers, " << e.frames << " frames";
  e.breakdown = b.str();
  return e;
}

void validate_geometry(const SwimSettings& settings) {
  const coupling::TankSpec& t = settings.tank;
  if (t.geometry != fluid::Geometry::axisymmetric) return;
  auto refuse = [](const std::string& why) {
    throw std::invalid_argument("tank.geometry = \"axisymmetric\": " + why);
  };
  if (t.symmetry == coupling::MirrorSymmetry::none)
    refuse("the slice is kept mirror-symmetric about the axis; tank.symmetry = \"none\" contradicts it");
  if (t.cells_x % 2 != 0) refuse("the axis is the centre line, a cell face: tank.cells[0] must be even");
  if (t.boundaries.periodic_x()) refuse("the radial direction cannot be periodic (tank.boundaries west/east)");
  if (t.pressure_solver == "multigrid") refuse("the multigrid pressure solver is planar only (use fft, direct or sor)");
  const double axis = 0.5 * t.width_m;
  for (std::size_t k = 0; k < settings.school.size(); ++k) {
    const JellyfishSpec& j = settings.school[k];
    if (std::abs(j.aperture_centre_m.x - axis) > 1e-9 * t.width_m)
      refuse("jellyfish " + std::to_string(k + 1) + " is a body of revolution about the axis: its position x = " +
             std::to_string(j.aperture_centre_m.x) + " m must be the tank's centre line, " + std::to_string(axis) + " m");
  }
  if (!settings.structures.empty())
    refuse("IB2d structures are planar and not supported in axisymmetric tanks");
}

namespace {

/// A body of the scene as validate_layout checks it.
struct Shape {
  std::string name;
  std::vector<Vec2> polygon;  ///< closed outline
  std::vector<Vec2> points;   ///< every point that must lie inside the tank
  std::string remedy;         ///< the fields that move or shrink it
};

/// The interval a point's coordinate must lie in along a side of length `length`: half a cell from
/// the walls, or along a periodic direction within one period either side of the tank (the
/// coupling wraps positions by whole periods: 3e15 m away was a NaN at the first step).
std::array<double, 2> allowed_span(double length, double margin, bool periodic) {
  return periodic ? std::array<double, 2>{-length, 2.0 * length} : std::array<double, 2>{margin, length - margin};
}

void check_inside(const Shape& s, const coupling::TankSpec& t) {
  const double margin = 0.5 * std::min(t.width_m / t.cells_x, t.height_m / t.cells_y);
  const auto x = allowed_span(t.width_m, margin, t.boundaries.periodic_x());
  const auto y = allowed_span(t.height_m, margin, t.boundaries.periodic_y());
  for (Vec2 p : s.points)
    if (!(p.x >= x[0] && p.x <= x[1] && p.y >= y[0] && p.y <= y[1])) {
      std::ostringstream m;
      m.precision(6);
      m << s.name << " reaches outside the tank: point (" << p.x << ", " << p.y << ") m is not inside [" << x[0]
        << ", " << x[1] << "] x [" << y[0] << ", " << y[1]
        << "] m (half a cell from the walls; along a periodic side, one tank length beyond it): " << s.remedy
        << ", or enlarge the tank (tank.width, tank.height)";
      throw std::invalid_argument(m.str());
    }
}

/// How to move or shrink jellyfish `k` (the first may be [jellyfish], the others are [[objects]]).
std::string jellyfish_remedy(std::size_t k) {
  const std::string where = k == 0 ? "field 'jellyfish.position' (or its [[objects]] table's 'position')"
                                   : "the 'position' of its [[objects]] table";
  return "move it (" + where + ") or make it smaller (diameter, height, tentacle_length)";
}

}  // namespace

void validate_layout(const SwimSettings& settings) {
  validate_geometry(settings);
  std::vector<Shape> shapes;
  for (std::size_t k = 0; k < settings.school.size(); ++k) {
    const Jellyfish j(settings.school[k]);
    shapes.push_back({"jellyfish " + std::to_string(k + 1), jellyfish_outline(j), j.body().points.position,
                      jellyfish_remedy(k)});
  }
  for (const ObstacleSpec& o : settings.obstacles) {
    validate(o);
    std::vector<Vec2> outline = obstacle_outline(o);
    shapes.push_back({o.name, outline, outline, "move it (its 'centre' or 'points') or make it smaller"});
  }
  for (const Ib2dObjectSpec& st : settings.structures) {
    std::vector<Vec2> points;
    for (Vec2 v : st.structure.vertices) points.push_back(v + st.offset_m);
    // No outline: IB2d structures are not checked for overlap.
    shapes.push_back({st.name, {}, points, "move it (its field 'offset') or check its .vertex file's coordinates"});
  }
  for (const Shape& s : shapes) check_inside(s, settings.tank);
  for (std::size_t a = 0; a < shapes.size(); ++a)
    for (std::size_t b = a + 1; b < shapes.size(); ++b)
      if (polygons_overlap(shapes[a].polygon, shapes[b].polygon))
        throw std::invalid_argument(shapes[a].name + " and " + shapes[b].name + " overlap; move them apart");
}

SwimSimulation::SwimSimulation(const SwimSettings& settings) : settings_(settings) {
  validate_geometry(settings_);
  // In axisymmetric water every jellyfish is a body of revolution about the tank's axis.
  for (JellyfishSpec& spec : settings_.school) spec.rings = settings_.tank.geometry == fluid::Geometry::axisymmetric;
  auto body = std::make_unique<elastic::Body>();
  for (const JellyfishSpec& spec : settings_.school) {
    school_.push_back(std::make_unique<Jellyfish>(spec));
    school_.back()->move_into(*body);
  }
  strain_reference_ = body->linear.rest_length;
  for (const std::unique_ptr<Jellyfish>& j : school_) {
    const JellyfishLayout& layout = j->layout();
    for (std::size_t k = 0; k < layout.muscle_springs.size(); ++k)
      strain_reference_[static_cast<std::size_t>(layout.muscle_springs[k])] = layout.muscle_uncontracted_m[k];
  }
  const double spacing = coupling::peskin_spacing(settings_.tank);
  for (const ObstacleSpec& o : settings_.obstacles) {
    validate(o);
    obstacles_.push_back(add_obstacle(o, spacing, *body));
    if (settings_.tank.geometry == fluid::Geometry::axisymmetric) make_ring_tethers(obstacles_.back(), spacing, *body);
  }
  // IB2d structures get the marker spacing IB2d's driver uses: half the smaller cell size.
  for (const Ib2dObjectSpec& st : settings_.structures) {
    validate(st);
    structures_.push_back(add_ib2d_object(st, spacing, *body));
  }
  strain_reference_.resize(body->linear.size(), 0.0);  // tethers have zero rest length: no strain
  for (std::size_t k = 0; k < structures_.size(); ++k) {
    const Ib2dParts& parts = structures_[k];
    for (std::size_t r = 0; r < parts.spring.size(); ++r)
      if (parts.spring[r] >= 0)
        strain_reference_[static_cast<std::size_t>(parts.spring[r])] = body->linear.rest_length[static_cast<std::size_t>(parts.spring[r])];
    set_strain_references(settings_.structures[k], parts, strain_reference_);
    for (int tether : parts.tethers) strain_reference_[static_cast<std::size_t>(tether)] = 0.0;
  }

  std::vector<int> mirror_partners;
  if (settings_.tank.symmetry != coupling::MirrorSymmetry::none) {
    if (const std::string problem = mirror_problem(*body, mirror_partners); !problem.empty()) {
      if (settings_.tank.symmetry == coupling::MirrorSymmetry::mirror)
        throw std::invalid_argument("tank.symmetry = \"mirror\" needs a scene that is its own mirror image: " +
                                    problem);
      if (settings_.tank.geometry == fluid::Geometry::axisymmetric)
        throw std::invalid_argument("tank.geometry = \"axisymmetric\" needs a scene that is its own mirror image "
                                    "about the axis: " + problem);
      mirror_note_ = "the scene is not its own mirror image: " + problem;
      mirror_partners.clear();
    }
  }
  // Each jellyfish sets its muscles (and steering joints) in the world's body.
  auto actuate = [this](double t, elastic::Body& body) {
    for (const std::unique_ptr<Jellyfish>& j : school_) j->actuate(t);
    for (std::size_t k = 0; k < structures_.size(); ++k) actuate_schedules(settings_.structures[k], structures_[k], t, body);
  };
  world_ = std::make_unique<coupling::World>(settings_.tank, std::move(body), settings_.coupling, actuate,
                                             std::move(mirror_partners));
}

SwimSimulation::~SwimSimulation() = default;

Vec2 SwimSimulation::structure_centroid(std::size_t i) const {
  const Ib2dParts& parts = structures_.at(i);
  std::vector<char> target(static_cast<std::size_t>(parts.vertex_count), 0);
  for (const elastic::Ib2dTarget& t : settings_.structures[i].structure.targets) target[static_cast<std::size_t>(t.point)] = 1;
  Vec2 sum{};
  int count = 0;
  for (int v = 0; v < parts.vertex_count; ++v)
    if (!target[static_cast<std::size_t>(v)]) sum += body().points.position[static_cast<std::size_t>(parts.first_point + v)], ++count;
  return count > 0 ? sum / static_cast<double>(count) : sum;
}

const Jellyfish& SwimSimulation::jellyfish(std::size_t i) const {
  if (i >= school_.size()) throw std::out_of_range("no jellyfish " + std::to_string(i) + " in the scene");
  return *school_[i];
}

std::string SwimSimulation::mirror_problem(const elastic::Body& body, std::vector<int>& partners) {
  if (std::string problem = mirror_spec_problem(settings_); !problem.empty()) return problem;
  std::vector<int> first_point;
  for (const std::unique_ptr<Jellyfish>& j : school_) first_point.push_back(static_cast<int>(j->first_point()));
  return mirror_body_problem(settings_, body, first_point, partners, jellyfish_mirror_);
}

void SwimSimulation::end_mirror_symmetry(const std::string& why) {
  if (!world_->mirror_symmetric()) return;
  world_->end_mirror_symmetry();
  std::ostringstream note;
  note.precision(4);
  note << "ended at t = " << time_s() << " s: " << why;
  mirror_note_ = note.str();
}

void SwimSimulation::edit_of_jellyfish(std::size_t j, const char* what) {
  if (world_->mirror_symmetric() && jellyfish_mirror_.at(j) != static_cast<int>(j))
    end_mirror_symmetry(std::string(what) + " of jellyfish " + std::to_string(j + 1) + " alone");
}

std::vector<Vec2> SwimSimulation::obstacle_outline(std::size_t i) const {
  std::vector<Vec2> p;
  for (int m : obstacles_.at(i).markers) p.push_back(body().points.position[static_cast<std::size_t>(m)]);
  return p;
}

void SwimSimulation::make_ring_tethers(const ObstacleParts& parts, double spacing, elastic::Body& body) const {
  // Each marker is a ring (a body of revolution's outline, e.g. a sphere on the axis): its tether
  // holds the whole ring, 2π r times the planar tether per metre of depth (r at least a quarter of
  // the spacing for markers on the axis, as the ring jellyfish's elements).
  const double axis = 0.5 * settings_.tank.width_m;
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    const double r = std::abs(body.points.position[static_cast<std::size_t>(parts.markers[k])].x - axis);
    body.linear.stiffness[static_cast<std::size_t>(parts.tethers[k])] *= 2.0 * std::numbers::pi * std::max(r, 0.25 * spacing);
  }
}

Vec2 SwimSimulation::obstacle_force(std::size_t i) const {
  const Vec2 f = obstacle_fluid_force(obstacles_.at(i), body());
  // Axisymmetric: the outline holds each ring twice (east and west), the points on the axis once,
  // and the coupling spreads half of the force on those (ImmersedBoundary::spread): the body of
  // revolution's force is half the sum. Along the axis only (the radial parts cancel).
  if (world_->axisymmetric()) return {0.0, 0.5 * f.y};
  return f;
}

double SwimSimulation::obstacle_leakage(std::size_t i) const {
  const ObstacleParts& parts = obstacles_.at(i);
  const fluid::Velocity& u = flow().velocity;
  const auto& x = body().points.position;
  const auto& v = body().points.velocity;
  double crossing = 0.0;
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    const auto a = static_cast<std::size_t>(parts.markers[k]);
    const auto b = static_cast<std::size_t>(parts.markers[(k + 1) % parts.markers.size()]);
    const Vec2 mid = 0.5 * (x[a] + x[b]);
    const Vec2 wall_velocity = 0.5 * (v[a] + v[b]);
    const Vec2 normal_times_length{x[b].y - x[a].y, x[a].x - x[b].x};  // outward for a counter-clockwise outline
    const Vec2 relative = Vec2{u.u.sample(mid), u.v.sample(mid)} - wall_velocity;
    // Axisymmetric: each element is a band of circumference 2π r, and appears twice (both halves).
    const double weight = world_->axisymmetric() ? std::numbers::pi * std::abs(mid.x - 0.5 * settings_.tank.width_m) : 1.0;
    crossing += weight * std::abs(dot(relative, normal_times_length));
  }
  return 0.5 * crossing;
}

std::string SwimSimulation::check() const {
  const elastic::Body& body = world_->body();
  std::string problem = coupling::check_stability(world_->fluid().state(), body, settings_.limits, &strain_reference_);
  if (!problem.empty()) return problem;
  for (std::size_t j = 0; j < school_.size(); ++j)
    if (polyline_self_intersects(school_[j]->umbrella_points()))
      return "structural instability: the umbrella of jellyfish " + std::to_string(j + 1) +
             " crossed itself (mesh inversion)";
  const double limit = settings_.obstacle_max_displacement_m > 0 ? settings_.obstacle_max_displacement_m
                                                                 : 2.0 * coupling::peskin_spacing(settings_.tank);
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    const ObstacleParts& parts = obstacles_[o];
    for (std::size_t k = 0; k < parts.markers.size(); ++k) {
      const Vec2 x = body.points.position[static_cast<std::size_t>(parts.markers[k])];
      const double stretch = norm(x - body.points.position[static_cast<std::size_t>(parts.targets[k])]);
      if (!(stretch <= limit))
        return "structural instability: " + settings_.obstacles[o].name + " was pushed " + format_length(stretch) +
               " off its place near (" + std::to_string(x.x) + ", " + std::to_string(x.y) +
               ") m, more than " + format_length(limit) + " (raise its stiffness)";
    }
  }
  return {};
}

bool SwimSimulation::finite_state() const {
  const elastic::Body& b = world_->body();
  const auto finite = [](Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); };
  return std::all_of(b.points.position.begin(), b.points.position.end(), finite) &&
         std::all_of(b.points.velocity.begin(), b.points.velocity.end(), finite);
}

SwimStep SwimSimulation::step(double max_dt_s) { return advance(std::min(world_->next_time_step(), max_dt_s)); }

SwimStep SwimSimulation::step_toward(double frame_time_s) {
  const double remaining = frame_time_s - time_s();
  const double natural = world_->next_time_step();
  return advance(natural >= remaining ? remaining : (natural > 0.5 * remaining ? 0.5 * remaining : natural));
}

SwimStep SwimSimulation::advance(double dt_s) {
  SwimStep s;
  s.dt_s = dt_s;
  if (!(s.dt_s >= settings_.coupling.min_time_step_s)) {
    s.failure = "numerical instability: the stable time step fell to " + std::to_string(s.dt_s) +
                " s, below min_time_step" + when(time_s(), steps());
    return s;
  }
  try {
    s.krylov_iterations = world_->step(s.dt_s).krylov.iterations;
  } catch (const std::bad_alloc&) {
    s.failure = "out of memory (std::bad_alloc) in a step" + when(time_s(), steps());
    return s;
  }
  if (std::string problem = check(); !problem.empty()) s.failure = problem + when(time_s(), steps());
  return s;
}

SwimRunStats SwimSimulation::run(const FrameCallback& on_frame, const sim::ProgressCallback& progress,
                                 std::int64_t frames_recorded, const std::function<bool()>& done) {
  run_start_ = std::chrono::steady_clock::now();
  SwimRunStats stats;
  const double duration = settings_.duration_s;
  sim::FrameClock clock = settings_.frame_clock(duration);
  for (std::int64_t k = 0; k < frames_recorded; ++k) clock.frame_emitted();
  sim::ClockedRun loop;
  loop.time = [this] { return time_s(); };
  loop.frame = [&](std::int64_t) { return on_frame ? on_frame(*this) : std::string(); };
  loop.step = [&](double frame_time) -> sim::StepResult {
    if (done && done()) return {sim::StepResult::Kind::stop, {}};
    const SwimStep s = step_toward(frame_time);
    if (s.failure.empty() || s.dt_s >= settings_.coupling.min_time_step_s) {
      smallest_step_s_ = std::min(smallest_step_s_, s.dt_s);
      largest_step_s_ = std::max(largest_step_s_, s.dt_s);
      krylov_iterations_ += s.krylov_iterations;
    }
    if (!s.failure.empty()) {
      // Keep the state that failed as a last frame, if it is finite (a non-finite one would make
      // every metric near it NaN): the failure itself is the message either way.
      if (on_frame && s.dt_s >= settings_.coupling.min_time_step_s && finite_state()) {
        try {
          on_frame(*this);
        } catch (const std::exception& e) {
          return sim::StepResult::failed_with(s.failure + " (its last frame could not be written: " + e.what() + ")");
        }
      }
      return sim::StepResult::failed_with(s.failure);
    }
    return {};
  };
  // Progress counts the coupling's steps (also those taken before run(), e.g. by the viewer).
  const sim::ProgressCallback steps_progress =
      progress ? sim::ProgressCallback([&](double t, double d, std::int64_t) { progress(t, d, steps()); })
               : sim::ProgressCallback();
  stats.failure = sim::run_frames(clock, loop, steps_progress).failure;
  stats.simulated_seconds = time_s();
  stats.steps = steps();
  stats.mirror_symmetric = world_->mirror_symmetric();
  stats.half_tank = world_->solving_half_tank();
  stats.symmetry_note = mirror_note_;
  stats.wall_seconds =
      earlier_wall_seconds_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
  stats.smallest_step_s = std::isfinite(smallest_step_s_) ? smallest_step_s_ : 0.0;
  stats.largest_step_s = largest_step_s_;
  stats.krylov_iterations = krylov_iterations_;
  return stats;
}

void SwimSimulation::archive(core::StateArchive& a) {
  world_->archive(a);
  for (std::size_t j = 0; j < school_.size(); ++j) {
    const core::StateArchive::Scope scope(a, "jellyfish_" + std::to_string(j + 1));
    school_[j]->archive(a);
  }
  for (std::size_t o = 0; o < obstacles_.size(); ++o) a.value("obstacle_" + std::to_string(o + 1) + ".shift", *obstacles_[o].shift);
  a.text("mirror_note", mirror_note_);
  const core::StateArchive::Scope scope(a, "run");
  a.value("smallest_step", smallest_step_s_);
  a.value("largest_step", largest_step_s_);
  a.value("krylov_iterations", krylov_iterations_);
  // Wall-clock so far (summary.json's wall_seconds counts every leg of a resumed run).
  double wall = earlier_wall_seconds_;
  if (!a.is_restoring() && run_start_ != std::chrono::steady_clock::time_point{})
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
  a.value("wall_seconds", wall);
  if (a.is_restoring()) earlier_wall_seconds_ = wall;
}

void SwimSimulation::save_state(core::StateArchive& a) const {
  if (a.is_restoring()) throw std::logic_error("save_state needs an archive made by StateArchive::saving()");
  // archive() saves by reading the members; the one function serves both directions.
  const_cast<SwimSimulation*>(this)->archive(a);
}

void SwimSimulation::restore_state(core::StateArchive& a) {
  if (!a.is_restoring()) throw std::logic_error("restore_state needs an archive made by StateArchive::restoring()");
  archive(a);
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
  if (target_m && world_->axisymmetric())
    throw std::invalid_argument("a ring jellyfish in an axisymmetric tank swims along the axis: it cannot steer");
  school_.at(j)->set_steer_target(target_m);
  if (target_m) end_mirror_symmetry("jellyfish " + std::to_string(j + 1) + " began to steer");
}
void SwimSimulation::set_viscosity(double nu_m2_per_s) { world_->set_viscosity(nu_m2_per_s); }

void SwimSimulation::stir(Vec2 at_m, Vec2 delta_velocity_m_per_s, double radius_m) {
  if (!(radius_m > 0)) throw std::invalid_argument("stir radius must be > 0");
  if (world_->axisymmetric()) {
    // A stir of axisymmetric water is a ring about the axis: its meridian east of the axis.
    const double axis = 0.5 * settings_.tank.width_m;
    if (at_m.x < axis) at_m.x = 2.0 * axis - at_m.x, delta_velocity_m_per_s.x = -delta_velocity_m_per_s.x;
    world_->stir(at_m, delta_velocity_m_per_s, radius_m);
    return;
  }
  end_mirror_symmetry("the fluid was stirred");
  world_->stir(at_m, delta_velocity_m_per_s, radius_m);
}

void SwimSimulation::move_jellyfish(std::size_t j, Vec2 delta_m) {
  if (world_->axisymmetric()) delta_m.x = 0.0;  // a ring jellyfish stays on the axis
  if (delta_m.x != 0.0 || jellyfish_mirror_.empty() || jellyfish_mirror_.at(j) != static_cast<int>(j))
    end_mirror_symmetry("jellyfish " + std::to_string(j + 1) + " was moved");
  Jellyfish& jellyfish = *school_.at(j);
  auto& position = world_->body().points.position;
  for (std::size_t p = 0; p < jellyfish.point_count(); ++p) position[jellyfish.first_point() + p] += delta_m;
}

void SwimSimulation::move_obstacle(std::size_t o, Vec2 delta_m) {
  ObstacleParts& parts = obstacles_.at(o);
  end_mirror_symmetry(settings_.obstacles.at(o).name + " was moved");
  *parts.shift += delta_m;
  auto& position = world_->body().points.position;
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    position[static_cast<std::size_t>(parts.markers[k])] += delta_m;
    position[static_cast<std::size_t>(parts.targets[k])] += delta_m;
  }
}

}  // namespace jellysim::jellyfish
