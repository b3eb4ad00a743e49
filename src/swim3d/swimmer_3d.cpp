#include "jellysim/swim3d/swimmer_3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace jellysim::swim3d {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

void require(bool ok, const std::string& field, const std::string& range) {
  if (!ok) throw std::invalid_argument("3D swimmer: field '" + field + "' is out of range " + range);
}

/// True when the pacemaker sits in the plane z = 0 (azimuth 0 or π), so the stroke is its own
/// mirror image in z.
bool pacemaker_in_the_slice_plane(const shell::ShellBellSpec& b) {
  return std::abs(std::sin(b.pacemaker_azimuth_rad)) < 1e-12;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec3 mean_of(std::span<const Vec3> x, std::size_t first, std::size_t count) {
  Vec3 c{};
  for (std::size_t i = first; i < first + count; ++i)
    for (std::size_t d = 0; d < 3; ++d) c[d] += x[i][d];
  for (double& v : c) v /= static_cast<double>(count);
  return c;
}

}  // namespace

std::string_view to_string(TankSymmetry3d s) {
  switch (s) {
    case TankSymmetry3d::automatic: return "auto";
    case TankSymmetry3d::none: return "none";
    case TankSymmetry3d::half: return "half";
    case TankSymmetry3d::quarter: return "quarter";
  }
  return "?";
}

TankSymmetry3d resolved_symmetry(const Swim3dSpec& s) {
  if (s.symmetry != TankSymmetry3d::automatic) return s.symmetry;
  if (!s.bell.pacemaker) return TankSymmetry3d::quarter;
  return pacemaker_in_the_slice_plane(s.bell) ? TankSymmetry3d::half : TankSymmetry3d::none;
}

void validate(const Swim3dSpec& s) {
  shell::validate(s.bell);
  for (int d = 0; d < 3; ++d) {
    require(s.tank_size_m[static_cast<std::size_t>(d)] > 0 && s.tank_size_m[static_cast<std::size_t>(d)] <= 100,
            "tank.size[" + std::to_string(d) + "]", "(0, 100] m");
    require(s.cells[static_cast<std::size_t>(d)] >= 4 && s.cells[static_cast<std::size_t>(d)] <= 4096,
            "tank.cells[" + std::to_string(d) + "]", "[4, 4096]");
  }
  const TankSymmetry3d sym = resolved_symmetry(s);
  const bool x_mirror = sym == TankSymmetry3d::quarter, z_mirror = sym != TankSymmetry3d::none;
  require(!x_mirror || s.cells[0] % 2 == 0, "tank.cells[0]", "even numbers (the mirror plane x = 0 halves the tank)");
  require(!z_mirror || s.cells[2] % 2 == 0, "tank.cells[2]", "even numbers (the mirror plane z = 0 halves the tank)");
  require(!(s.bell.pacemaker && x_mirror), "tank.symmetry",
          "none or half with a pacemaker (it fires one side first: no mirror plane x = 0)");
  require(!(s.bell.pacemaker && z_mirror && !pacemaker_in_the_slice_plane(s.bell)), "tank.symmetry",
          "none unless the pacemaker's azimuth is 0 or π (the mirror plane z = 0 must be its own)");
  const double r = 0.5 * s.bell.slice.diameter_m;
  require(2.0 * r < std::min(s.tank_size_m[0], s.tank_size_m[2]), "jellyfish.diameter",
          "(0, the tank's width and depth)");
  require(s.aperture_height_m - s.bell.slice.tentacle_length_m > 0 &&
              s.aperture_height_m + s.bell.slice.height_m < s.tank_size_m[1],
          "jellyfish.position", "heights that keep the bell and its tentacles inside the tank");
  require(s.density_kg_per_m3 >= 1e-3 && s.density_kg_per_m3 <= 1e5, "tank.density", "[0.001, 100000] kg/m³");
  require(s.viscosity_m2_per_s >= 0 && std::isfinite(s.viscosity_m2_per_s), "tank.viscosity", "[0, inf) m²/s");
  require(s.max_time_step_s > 0 && s.max_time_step_s <= 0.1, "time_step", "(0, 0.1] s");
  require(s.frames_per_cycle >= 1 && s.frames_per_cycle <= 10000, "frames_per_cycle", "[1, 10000]");
  require(s.threads >= 0 && s.threads <= 1024, "threads", "[0, 1024] (0: all cores)");
}

fluid3d::Grid3d solved_grid(const Swim3dSpec& s) {
  const TankSymmetry3d sym = resolved_symmetry(s);
  fluid3d::Index3 n = s.cells;
  Vec3 size = s.tank_size_m;
  Vec3 origin{-0.5 * size[0], 0.0, -0.5 * size[2]};
  if (sym == TankSymmetry3d::quarter) n[0] /= 2, size[0] *= 0.5, origin[0] = 0.0;
  if (sym != TankSymmetry3d::none) n[2] /= 2, size[2] *= 0.5, origin[2] = 0.0;
  return fluid3d::Grid3d(n, size, origin);
}

fluid3d::FluidSettings3d fluid_settings(const Swim3dSpec& s) {
  fluid3d::FluidSettings3d f;
  f.method = s.method;
  f.convection = s.convection;
  f.density_kg_per_m3 = s.density_kg_per_m3;
  f.viscosity_m2_per_s = s.viscosity_m2_per_s;
  f.threads = s.threads;
  f.boundaries = fluid3d::Boundaries3d::closed_box();
  for (auto& a : f.boundaries.axis) a.symmetry = {true, true};  // free-slip walls (§7.1) and mirror planes
  return f;
}

BellPose bell_pose(const shell::ShellBell& bell, std::span<const Vec3> x) {
  const shell::RevolvedMesh& s = bell.surface();
  const std::size_t margin = s.rings.first.size() - 1;
  const Vec3 rim = mean_of(x, static_cast<std::size_t>(s.rings.first[margin]), static_cast<std::size_t>(s.rings.count[margin]));
  BellPose p;
  p.centroid = mean_of(x, 0, s.mesh.vertices.size());
  p.axis = sub(x[static_cast<std::size_t>(s.rings.apex)], rim);
  const double length = std::sqrt(dot(p.axis, p.axis));
  for (double& a : p.axis) a /= length;
  p.heading_deg = kDegrees * std::atan2(-p.axis[0], p.axis[1]);
  p.tilt_deg = kDegrees * std::acos(std::clamp(p.axis[1], -1.0, 1.0));
  return p;
}

Swimmer3d::Swimmer3d(const Swim3dSpec& spec) : spec_(spec) {
  validate(spec_);
  bell_ = std::make_unique<shell::ShellBell>(spec_.bell);
  forces_ = std::make_unique<ShellForces3d>(*bell_);
  fluid_ = fluid3d::make_fluid_solver_3d(solved_grid(spec_), fluid_settings(spec_));
  markers_ = ib3d::Markers3d(shell_markers(*bell_, {0.0, spec_.aperture_height_m, 0.0}));
  ib3d::CouplingSettings3d c = spec_.coupling;
  c.threads = spec_.threads;
  coupling_ = std::make_unique<ib3d::ImmersedBoundary3d>(*fluid_, markers_, *forces_, c);
}

Swimmer3d::~Swimmer3d() = default;

double Swimmer3d::frame_interval_s() const {
  return 1.0 / (spec_.bell.slice.frequency_hz * spec_.frames_per_cycle);
}

Frame3d Swimmer3d::frame() const {
  Frame3d f;
  f.time_s = time_s();
  f.points = markers_.position;
  const BellPose pose = bell_pose(*bell_, f.points);
  f.centroid = pose.centroid;
  f.axis = pose.axis;
  f.heading_deg = pose.heading_deg;
  f.tilt_deg = pose.tilt_deg;
  f.velocity = mean_of(markers_.velocity, 0, bell_->surface().mesh.vertices.size());
  shell::Vector stacked(3 * static_cast<Eigen::Index>(f.points.size()));
  for (std::size_t i = 0; i < f.points.size(); ++i)
    for (std::size_t d = 0; d < 3; ++d) stacked(static_cast<Eigen::Index>(3 * i + d)) = f.points[i][d];
  f.cavity_volume_m3 = bell_->cavity_volume(stacked);
  f.steps = timings_.steps;
  f.krylov_iterations = krylov_since_frame_;
  return f;
}

// Equal coupled steps land on the frame's time: n = ⌈(t_frame − t) / Δt_max⌉ with Δt_max the
// smaller of the spec's and the fluid's present limit (a frame clock of the frame index, so the
// times do not drift).
bool Swimmer3d::step_toward_frame() {
  if (frame_reached_) krylov_since_frame_ = 0, frame_reached_ = false;
  const double target = static_cast<double>(frame_index_ + 1) * frame_interval_s();
  const double limit = std::min(spec_.max_time_step_s, fluid_->stable_time_step());
  const double left = target - time_s();
  const double dt = left / std::ceil(left / limit - 1e-9);
  const auto t0 = std::chrono::steady_clock::now();
  const ib3d::CoupledStepReport3d r = coupling_->step(dt);
  timings_.total_s += seconds_since(t0);
  timings_.transfer_s += r.transfer_s, timings_.fluid_s += r.fluid_s, timings_.krylov_s += r.krylov_s;
  ++timings_.steps;
  timings_.krylov_iterations += r.krylov_iterations;
  krylov_since_frame_ += r.krylov_iterations;
  if (!r.converged)
    throw std::runtime_error("3D swimmer: the semi-implicit solve did not converge at t = " + std::to_string(time_s()) +
                             " s (relative residual " + std::to_string(r.relative_residual) + ")");
  if (target - time_s() > 1e-12 * target) return false;
  ++frame_index_;
  frame_reached_ = true;
  return true;
}

void Swimmer3d::archive(core::StateArchive& a) {
  const core::StateArchive::Scope scope(a, "swimmer3d");
  fluid_->archive(a);
  coupling_->archive(a);
  a.value("frame_index", frame_index_);
  a.value("krylov_since_frame", krylov_since_frame_);
  a.value("frame_reached", frame_reached_);
  a.value("timings", timings_);
}

Frame3d Swimmer3d::advance_frame() {
  while (!step_toward_frame()) {
  }
  return frame();
}

SwimSummary3d summarize(const std::vector<Frame3d>& frames, int frames_per_cycle) {
  SwimSummary3d s;
  if (frames.empty()) return s;
  const Frame3d& first = frames.front();
  const auto per = static_cast<std::size_t>(frames_per_cycle);
  for (std::size_t end = per; end < frames.size(); end += per) {
    const Frame3d& a = frames[end - per];
    const Frame3d& b = frames[end];
    s.cycle_distance_m.push_back(dot(sub(b.centroid, a.centroid), first.axis));
    s.cycle_heading_deg.push_back(std::remainder(b.heading_deg - a.heading_deg, 360.0));  // through ±180° too
  }
  const auto mean_after_first = [](const std::vector<double>& v) {
    if (v.size() < 2) return v.empty() ? NAN : v.front();
    double sum = 0.0;
    for (std::size_t k = 1; k < v.size(); ++k) sum += v[k];
    return sum / static_cast<double>(v.size() - 1);
  };
  if (!s.cycle_distance_m.empty()) s.first_cycle_m = s.cycle_distance_m.front();
  s.distance_per_cycle_m = s.cycle_distance_m.size() > 1 ? mean_after_first(s.cycle_distance_m) : NAN;
  s.heading_change_deg_per_cycle = mean_after_first(s.cycle_heading_deg);
  const Frame3d& last = frames.back();
  s.final_heading_deg = last.heading_deg;
  s.final_tilt_deg = last.tilt_deg;
  const Vec3 moved = sub(last.centroid, first.centroid);
  const double along = dot(moved, first.axis);
  s.sideways_m = std::sqrt(std::max(0.0, dot(moved, moved) - along * along));
  return s;
}

}  // namespace jellysim::swim3d
