#include "jellysim/coupling/world.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/elastic/body_mirror.hpp"
#include "jellysim/fluid/flow_mirror.hpp"

namespace jellysim::coupling {

double peskin_spacing(const TankSpec& tank) {
  return 0.5 * std::min(tank.width_m / tank.cells_x, tank.height_m / tank.cells_y);
}

World::World(const TankSpec& tank, std::unique_ptr<elastic::Body> body, const CouplingSettings& coupling,
             Actuator actuate, std::vector<int> mirror_partners)
    : tank_(tank),
      coupling_settings_(coupling),
      actuate_(std::move(actuate)),
      body_(std::move(body)),
      mirror_partner_(std::move(mirror_partners)) {
  if (!body_) throw std::invalid_argument("a world needs a body (it may have no points)");
  if (!mirror_partner_.empty() && mirror_partner_.size() != body_->points.size())
    throw std::invalid_argument("the mirror partners must name one point per point of the body");
  mirror_active_ = !mirror_partner_.empty();
  if (axisymmetric()) {
    if (!mirror_active_)
      throw std::invalid_argument("an axisymmetric tank needs a scene that is its own mirror image about the axis "
                                  "(the centre line x = width/2): the slice of a body of revolution");
    if (tank_.cells_x % 2 != 0)
      throw std::invalid_argument("an axisymmetric tank needs an even number of cells across (the axis is a cell face)");
  }
  half_tank_ = mirror_active_ && (tank_.half_tank || axisymmetric()) && tank_.cells_x % 2 == 0;
  fluid_ = make_fluid(half_tank_);
  coupling_ = make_coupling(half_tank_);
  if (tank_.tracers_per_side > 0) {
    const double margin_x = 0.5 * tank_.width_m / tank_.tracers_per_side;
    const double margin_y = 0.5 * tank_.height_m / tank_.tracers_per_side;
    tracers_ = fluid::Tracers::lattice({margin_x, margin_y}, {tank_.width_m - margin_x, tank_.height_m - margin_y},
                                       tank_.tracers_per_side, tank_.tracers_per_side);
  }
}

World::~World() = default;

std::unique_ptr<fluid::FluidSolver> World::make_fluid(bool east_half) const {
  const fluid::MacGrid whole(tank_.cells_x, tank_.cells_y, tank_.width_m, tank_.height_m);
  fluid::FluidSettings fs;
  fs.viscosity_m2_per_s = fluid_ ? fluid_->settings().viscosity_m2_per_s : tank_.viscosity_m2_per_s;  // live edits stay
  fs.density_kg_per_m3 = tank_.density_kg_per_m3;
  fs.boundaries = tank_.boundaries;
  if (east_half) {
    // The centre line is a symmetry plane: free slip (u = 0, v and p even). A periodic tank's
    // seam is one too.
    fs.boundaries.west = {fluid::BoundaryType::free_slip, {}};
    if (tank_.boundaries.periodic_x()) fs.boundaries.east = {fluid::BoundaryType::free_slip, {}};
  }
  if (east_half) fs.geometry = tank_.geometry;  // the axis is the half tank's west side
  fs.convection = tank_.convection;
  fs.advection = tank_.advection;
  fs.pressure_solver = tank_.pressure_solver;
  fs.pressure.relative_tolerance = tank_.pressure_tolerance;
  fs.diffusion_tolerance = std::min(fs.diffusion_tolerance, tank_.pressure_tolerance);
  fs.safety_factor = 1.0;  // the coupling chooses Δt; the Eulerian solver only guards it
  auto fluid = fluid::make_fluid_solver(tank_.solver, east_half ? fluid::east_half(whole) : whole, fs);
  if (tank_.current_m_per_s.x != 0.0 || tank_.current_m_per_s.y != 0.0) {
    fluid->state().velocity.u.fill(tank_.current_m_per_s.x);
    fluid->state().velocity.v.fill(tank_.current_m_per_s.y);
    fluid->apply_boundaries();
  }
  return fluid;
}

std::unique_ptr<ImmersedBoundary> World::make_coupling(bool east_half) {
  CouplingSettings c = coupling_settings_;
  c.west_mirror = east_half && !axisymmetric();  // rings fold across the axis by themselves
  auto coupling = std::make_unique<ImmersedBoundary>(*fluid_, *body_, c, actuate_);
  if (mirror_active_) coupling->set_mirror_symmetry(mirror_partner_);
  return coupling;
}

CoupledStepReport World::step(double dt_s) {
  const CoupledStepReport report = coupling_->step(dt_s);
  if (mirror_active_) {
    if (!half_tank_) fluid::keep_mirror_symmetric_part(fluid_->state());  // the half tank is symmetric by construction
    elastic::keep_mirror_symmetric_part(*body_, mirror_partner_, 0.5 * tank_.width_m);
  }
  if (!tracers_.positions().empty()) tracers_.advect(flow().velocity, tank_.boundaries, dt_s);
  return report;
}

const fluid::FlowState& World::flow() const {
  if (!half_tank_) return fluid_->state();
  if (unfolded_step_ != steps()) {
    fluid::unfold_east_half(fluid_->state(), unfolded_, tank_.boundaries);
    unfolded_step_ = steps();
  }
  return unfolded_;
}

void World::leave_half_tank() {
  if (!half_tank_) return;
  fluid::FlowState whole;
  fluid::unfold_east_half(fluid_->state(), whole, tank_.boundaries);
  std::unique_ptr<fluid::FluidSolver> fluid = make_fluid(false);
  fluid->state().velocity = whole.velocity;
  fluid->state().pressure = whole.pressure;
  fluid->set_time_s(fluid_->time_s());
  std::unique_ptr<ImmersedBoundary> previous = std::move(coupling_);
  fluid_ = std::move(fluid);  // the previous coupling refers to the old fluid: keep it alive until here
  half_tank_ = false;
  coupling_ = make_coupling(false);
  coupling_->continue_from(*previous);
}

namespace {

/// What a run changes in a body: the points' motion and the springs that muscles, steering and
/// live edits actuate. The topology is the scene's (rebuilt from it).
void archive_body(core::StateArchive& a, elastic::Body& b) {
  const core::StateArchive::Scope scope(a, "body");
  a.values("position", std::span(b.points.position));
  a.values("velocity", std::span(b.points.velocity));
  a.values("linear.stiffness", std::span(b.linear.stiffness));
  a.values("linear.rest_length", std::span(b.linear.rest_length));
  a.values("angular.stiffness", std::span(b.angular.stiffness));
  a.values("angular.rest_angle", std::span(b.angular.rest_angle));
  a.values("torsional.curvature", std::span(b.torsional.curvature));
  a.values("non_invariant.curvature", std::span(b.non_invariant.curvature));
  a.values("power.rest_length", std::span(b.power.rest_length));
}

}  // namespace

void World::archive(core::StateArchive& a) {
  const core::StateArchive::Scope scope(a, "world");
  bool mirror = mirror_active_;
  a.value("mirror_symmetric", mirror);
  if (a.is_restoring() && mirror != mirror_active_) {
    if (mirror) throw core::StateMismatch("the checkpoint keeps a mirror symmetry this scene does not have");
    end_mirror_symmetry();  // a live edit had ended it
  }
  archive_body(a, *body_);
  fluid_->archive(a);
  coupling_->archive(a);
  a.vector("tracers", tracers_.positions());
  unfolded_step_ = -1;  // flow() of the half tank is unfolded anew
}

void World::end_mirror_symmetry() {
  if (!mirror_active_) return;
  if (axisymmetric())
    throw std::invalid_argument("an axisymmetric tank is symmetric about its axis by construction: this edit would "
                                "break the symmetry (use tank.geometry = \"planar\")");
  mirror_active_ = false;
  leave_half_tank();
  coupling_->set_mirror_symmetry({});
}

void World::stir(Vec2 at_m, Vec2 delta_velocity_m_per_s, double radius_m) {
  if (!(radius_m > 0)) throw std::invalid_argument("stir radius must be > 0");
  // Axisymmetric water: a splat of the (r, z) half plane is a ring about the axis (the symmetry stays).
  if (!axisymmetric()) end_mirror_symmetry();
  auto splat = [&](fluid::Field& f, double amount) {
    for (int j = 0; j < f.count_y(); ++j)
      for (int i = 0; i < f.count_x(); ++i) {
        const double r2 = norm_squared(f.position(i, j) - at_m) / (radius_m * radius_m);
        if (r2 < 9.0) f(i, j) += amount * std::exp(-r2);
      }
  };
  splat(fluid_->state().velocity.u, delta_velocity_m_per_s.x);
  splat(fluid_->state().velocity.v, delta_velocity_m_per_s.y);
  fluid_->apply_boundaries();
}

}  // namespace jellysim::coupling
