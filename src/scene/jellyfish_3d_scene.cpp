#include "jellysim/scene/jellyfish_3d_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/fluid/schemes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace jellysim::scene {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr const char* kSee = " (docs/three-d.md, \"The 3D scene\")";

/// A field that changes what is simulated but that the 3D model does not have, and why.
struct Unmodelled {
  const char* key;
  const char* why;
};
constexpr Unmodelled kUnmodelledIn3d[] = {
    {"objects", "the 3D tank holds one jellyfish and no obstacles"},
    {"jellyfish.enabled", "the 3D tank holds its jellyfish"},
    {"jellyfish.tilt_deg", "the 3D bell starts upright, its axis along +y"},
    {"jellyfish.elastic_model", "the shell's material is the continuum model's"},
    {"jellyfish.controller", "the shell's muscles follow the open-loop contraction"},
    {"jellyfish.steering", "the 3D bell turns by its pacemaker (jellyfish.pacemaker)"},
    {"tank.boundaries", "the 3D tank's walls are free-slip"},
    {"tank.current", "the 3D water starts at rest"},
    {"tank.pressure_solver", "the 3D pressure solve is the FFT"},
};

/// Refused unless left at their defaults: silently ignored, they would mislead.
void refuse_unmodelled(const Reader& r) {
  for (const auto& [key, why] : kUnmodelledIn3d) {
    if (r.holds_default(key)) continue;
    const std::string value = r.table().at(key).type == Type::tables
                                  ? std::to_string(r.config().array_size(key)) + " entries"
                                  : r.config().literal(key);
    throw InputError("field '" + std::string(key) + "' = " + value + " is not modelled with tank.geometry = \"3d\" (" +
                     why + "): leave it at its default " + r.table().at(key).value + kSee);
  }
}

/// tank.size [W, H, D], or [0, 0, 0]: [tank.width, tank.height, tank.width] (m).
swim3d::Vec3 read_tank_size(const Reader& r) {
  const std::vector<double> size = r.numbers("tank.size");
  if (std::all_of(size.begin(), size.end(), [](double v) { return v == 0.0; }))
    return {r.number("tank.width"), r.number("tank.height"), r.number("tank.width")};
  if (std::any_of(size.begin(), size.end(), [](double v) { return !(v > 0.0); }))
    throw InputError("field 'tank.size' = " + r.config().literal("tank.size") +
                     " is out of range: [width, height, depth], each in (0, 100] m, or [0, 0, 0] for [tank.width, "
                     "tank.height, tank.width]");
  return {size[0], size[1], size[2]};
}

/// tank.cells [nx, ny, nz]: the whole tank's cells.
fluid3d::Index3 read_cells(const Reader& r) {
  const std::vector<std::int64_t> cells = r.integers("tank.cells");
  if (cells.size() != 3)
    throw InputError("field 'tank.cells' has " + std::to_string(cells.size()) +
                     " entries: with tank.geometry = \"3d\" it must have 3, [nx, ny, nz] (the whole tank's cells), each "
                     "in [4, 4096]");
  return {static_cast<int>(cells[0]), static_cast<int>(cells[1]), static_cast<int>(cells[2])};
}

double smallest_cell_m(const swim3d::Swim3dSpec& s) {
  double h = s.tank_size_m[0] / s.cells[0];
  for (std::size_t d = 1; d < 3; ++d) h = std::min(h, s.tank_size_m[d] / s.cells[d]);
  return h;
}

/// The shell bell (docs/three-d.md, "Part 3"): the slice's shape, material and stroke as the 2D
/// scene reads them, the mesh's edge, the pacemaker and the tentacle rods.
shell::ShellBellSpec read_shell_bell(const config::Config& c, const Reader& r, double cell_m) {
  shell::ShellBellSpec b;
  b.slice = read_jellyfish_body(c);
  const double edge = r.number("jellyfish.shell_edge");
  b.target_edge_m = edge > 0.0 ? edge : 0.5 * cell_m;  // Peskin's rule, as the slice's markers
  const double d = b.slice.diameter_m;
  if (!(b.target_edge_m >= 1e-3 * d && b.target_edge_m <= 0.5 * d))
    throw InputError("field 'jellyfish.shell_edge' = " + config::format_number(edge) + " gives an edge of " +
                     config::format_number(b.target_edge_m) + " m: it must be in [diameter / 1000, diameter / 2] = [" +
                     config::format_number(1e-3 * d) + ", " + config::format_number(0.5 * d) +
                     "] m (0: half a fluid cell)");
  b.pacemaker = r.boolean("jellyfish.pacemaker");
  b.pacemaker_azimuth_rad = r.number("jellyfish.pacemaker_azimuth_deg") * kDegree;
  b.conduction_speed_m_per_s = r.number("jellyfish.conduction_speed");
  b.tentacle_count = b.slice.tentacle_length_m > 0.0 ? static_cast<int>(r.integer("jellyfish.tentacle_count")) : 0;
  return b;
}

/// jellyfish.position [0, y]: the aperture's height y, the axis on the centre line x = z = 0.
double read_aperture_height(const Reader& r, const swim3d::Swim3dSpec& s) {
  const Vec2 p = r.vec2("jellyfish.position");
  const std::string given = "field 'jellyfish.position' = [" + config::format_number(p.x) + ", " +
                            config::format_number(p.y) + "]";
  if (p.x != 0.0)
    throw InputError(given + ": the 3D bell's axis is the tank's centre line x = z = 0 (the tank spans x in [-W/2, "
                     "W/2]): give [0, aperture height]");
  const double low = s.bell.slice.tentacle_length_m, high = s.tank_size_m[1] - s.bell.slice.height_m;
  if (!(p.y > low && p.y < high))
    throw InputError(given + ": the aperture's height must be in (tentacle_length, tank height - bell height) = (" +
                     config::format_number(low) + ", " + config::format_number(high) +
                     ") m, so that the bell and its tentacles are inside the tank");
  return p.y;
}

/// The water: density, viscosity and the 3D fluid's method (docs/three-d.md, "The solver").
void read_water(const Reader& r, swim3d::Swim3dSpec& s) {
  s.density_kg_per_m3 = r.number("tank.density");
  s.viscosity_m2_per_s = r.number("tank.viscosity");
  if (r.choice("tank.solver") == "eulerian") {
    s.method = fluid3d::FluidMethod3d::eulerian;
    const std::string convection = r.choice("tank.convection");
    if (convection != "koren" && convection != "van-leer")
      throw InputError("field 'tank.convection' = \"" + convection +
                       "\": the 3D Eulerian step's convection is koren or van-leer (limited second order)" + kSee);
    s.convection = *fluid::convection_scheme_from_string(convection);
    return;
  }
  s.method = fluid3d::FluidMethod3d::semi_lagrangian;
  if (const std::string advection = r.choice("tank.advection"); advection != "maccormack")
    throw InputError("field 'tank.advection' = \"" + advection +
                     "\": the 3D semi-Lagrangian step advects with maccormack" + kSee);
}

/// The coupled step (ib3d): scheme, kernel, the Krylov solve, the largest step and the threads.
void read_coupling(const Reader& r, swim3d::Swim3dSpec& s) {
  s.coupling.scheme = r.choice("coupling.scheme") == "explicit" ? ib3d::Scheme3d::explicit_euler
                                                                : ib3d::Scheme3d::semi_implicit;
  s.coupling.kernel = *coupling::kernel_from_string(r.choice("coupling.kernel"));
  s.coupling.krylov_tolerance = r.number("coupling.krylov_tolerance");
  s.coupling.krylov_max_iterations = static_cast<int>(r.integer("coupling.krylov_max_iterations"));
  s.max_time_step_s = r.number("coupling.max_dt");
  if (s.max_time_step_s > 0.1)
    throw InputError("field 'coupling.max_dt' = " + config::format_number(s.max_time_step_s) +
                     " is out of range for the 3D swimmer: (0, 0.1] s");
  s.threads = static_cast<int>(r.integer("coupling.threads"));
}

/// tank.symmetry: auto and mirror solve the part the stroke's mirror planes allow (mirror insists
/// on one), none the whole tank.
swim3d::TankSymmetry3d read_symmetry(const Reader& r, const swim3d::Swim3dSpec& s) {
  const std::string symmetry = r.choice("tank.symmetry");
  if (symmetry == "none") return swim3d::TankSymmetry3d::none;
  if (symmetry == "mirror" && swim3d::resolved_symmetry(s) == swim3d::TankSymmetry3d::none)
    throw InputError("field 'tank.symmetry' is \"mirror\", but the stroke has no mirror plane: the pacemaker at "
                     "jellyfish.pacemaker_azimuth_deg = " + r.config().literal("jellyfish.pacemaker_azimuth_deg") +
                     " fires off the plane z = 0 (use \"auto\" or \"none\", or an azimuth of 0 or 180)");
  return swim3d::TankSymmetry3d::automatic;
}

/// A mirror plane halves the tank through a cell face: an even count of cells across it.
void check_mirror_cells(const Reader& r, const swim3d::Swim3dSpec& s) {
  const swim3d::TankSymmetry3d sym = swim3d::resolved_symmetry(s);
  const auto refuse = [&](const char* axis, const char* plane) {
    throw InputError("field 'tank.cells' = " + r.config().literal("tank.cells") + ": " + axis +
                     " must be even, the mirror plane " + plane + " of the " + std::string(swim3d::to_string(sym)) +
                     " tank halves it (tank.symmetry = \"none\" solves the whole tank)");
  };
  if (sym == swim3d::TankSymmetry3d::quarter && s.cells[0] % 2 != 0) refuse("nx", "x = 0");
  if (sym != swim3d::TankSymmetry3d::none && s.cells[2] % 2 != 0) refuse("nz", "z = 0");
}

/// Frames per cycle (output.frames_per_cycle, or the nearest to the frame interval or rate) and
/// the frames of the duration, rounded to the nearest whole number.
void read_frames(const Reader& r, Swim3dSettings& s) {
  jellyfish::SwimSettings clock;
  clock.duration_s = s.duration_s = r.number("duration");
  read_frame_rate(r, clock);
  const double f = s.spec.bell.slice.frequency_hz;
  auto n = static_cast<double>(r.integer("output.frames_per_cycle"));
  if (n > 0.0 && !(clock.frames_per_second == 0.0 && r.holds_default("output.frame_interval")))
    throw InputError("fields 'output.frames_per_cycle' and " +
                     std::string(clock.frames_per_second > 0.0 ? "'output.fps'" : "'output.frame_interval'") +
                     " both give the frame rate: give one of them");
  if (n == 0.0) n = std::max(1.0, std::round(1.0 / (f * clock.frame_interval_s)));
  if (n > 10000.0)
    throw InputError("field 'output.frame_interval' = " + config::format_number(clock.frame_interval_s) + " s gives " +
                     config::format_number(n) + " frames per cycle: the 3D run records at most 10000 a cycle");
  s.spec.frames_per_cycle = static_cast<int>(n);
  const double frames = std::round(s.duration_s * f * n);
  if (!(frames <= kMaxFrames))
    throw InputError("field 'duration' = " + config::format_number(s.duration_s) + " s asks for " +
                     config::format_number(frames) + " frames; at most " + config::format_number(kMaxFrames));
  s.frames = std::max<std::int64_t>(1, static_cast<std::int64_t>(frames));
}

/// The water's memory on the solved grid against the budget (core/memory.hpp), before anything is built.
void check_memory(Swim3dSettings& s) {
  const fluid3d::Grid3d g = swim3d::solved_grid(s.spec);
  s.estimated_memory_bytes = static_cast<double>(fluid3d::estimated_memory_bytes_3d(g, swim3d::fluid_settings(s.spec)));
  const core::MemoryBudget budget = core::memory_budget();
  if (!(s.estimated_memory_bytes <= static_cast<double>(budget.bytes)))
    throw InputError("the 3D run would need about " + core::format_bytes(s.estimated_memory_bytes) + " for its water (" +
                     std::to_string(g.cell_count()) + " cells solved), more than the budget of " +
                     core::format_bytes(static_cast<double>(budget.bytes)) + " (" + budget.source +
                     "): coarsen tank.cells or raise --memory-limit");
}

}  // namespace

double Swim3dSettings::end_time_s() const {
  return static_cast<double>(frames) / (spec.bell.slice.frequency_hz * spec.frames_per_cycle);
}

bool is_3d_scene(const config::Config& c) {
  return c.has("tank.geometry") && Reader(c, jellyfish_scene()).choice("tank.geometry") == "3d";
}

Swim3dSettings read_swim3d_settings(const config::Config& c) {
  const Reader r(c, jellyfish_scene());
  r.validate_all();
  refuse_unmodelled(r);
  Swim3dSettings s;
  swim3d::Swim3dSpec& spec = s.spec;
  spec.tank_size_m = read_tank_size(r);
  spec.cells = read_cells(r);
  spec.bell = read_shell_bell(c, r, smallest_cell_m(spec));
  spec.aperture_height_m = read_aperture_height(r, spec);
  read_water(r, spec);
  read_coupling(r, spec);
  spec.symmetry = read_symmetry(r, spec);
  check_mirror_cells(r, spec);
  read_frames(r, s);
  s.vtk = r.boolean("output.vtk");
  try {
    swim3d::validate(spec);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  check_memory(s);
  return s;
}

config::Config axisymmetric_counterpart(const config::Config& c, const config::Config& builtin) {
  const Swim3dSettings s = read_swim3d_settings(c);
  const swim3d::Swim3dSpec& spec = s.spec;
  config::Config a = c;
  a.set("tank.geometry=\"axisymmetric\"");
  for (const char* key : fields_of_3d()) a.set(std::string(key) + "=" + builtin.literal(key));
  for (const char* key : {"tank.solver", "tank.convection", "tank.advection", "tank.symmetry", "coupling.kernel",
                          "coupling.max_dt", "coupling.threads", "output.fps"})
    a.set(std::string(key) + "=" + builtin.literal(key));
  a.set("tank.width=" + config::format_number(spec.tank_size_m[0]));
  a.set("tank.height=" + config::format_number(spec.tank_size_m[1]));
  a.set("tank.cells=[" + std::to_string(spec.cells[0]) + ", " + std::to_string(spec.cells[1]) + "]");
  a.set("jellyfish.position=[" + config::format_number(0.5 * spec.tank_size_m[0]) + ", " +
        config::format_number(spec.aperture_height_m) + "]");
  a.set("output.frame_interval=" +
        config::format_number(1.0 / (spec.frames_per_cycle * spec.bell.slice.frequency_hz)));
  return a;
}

}  // namespace jellysim::scene
