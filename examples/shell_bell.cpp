// The bell as an elastic shell (docs/three-d.md, "Part 3"), without water: the built-in bell's
// stroke with the pacemaker on one side of the margin, drag 20 /s standing in for the water. Writes
// the surface and tentacles as OBJ files at rest and at the times asked for, and prints each side's
// margin displacement and the cavity volume:
//   shell_bell OUT_DIR [T1 T2 ...]      (times in seconds; default 0.1 0.3)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "jellysim/ode/leapfrog.hpp"
#include "jellysim/shell/shell_bell.hpp"
#include "jellysim/shell/shell_dynamics.hpp"

namespace js = jellysim::shell;

namespace {

void write_obj(const std::string& path, const js::ShellBell& bell, const js::Vector& x) {
  std::ofstream out(path);
  if (!out) {
    std::fprintf(stderr, "shell_bell: cannot write %s\n", path.c_str());
    std::exit(2);
  }
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) out << "v " << x(3 * i) << ' ' << x(3 * i + 1) << ' ' << x(3 * i + 2) << '\n';
  for (const auto& t : bell.surface().mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  for (const auto& strand : bell.tentacles()) {
    out << 'l';
    for (int p : strand) out << ' ' << p + 1;
    out << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: shell_bell OUT_DIR [T1 T2 ...]\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::error_code made;
  std::filesystem::create_directories(dir, made);  // a failure shows when the first file is written
  std::vector<double> times;
  for (int a = 2; a < argc; ++a) times.push_back(std::atof(argv[a]));
  if (times.empty()) times = {0.1, 0.3};
  js::ShellBellSpec spec;
  spec.target_edge_m = 0.003;
  spec.pacemaker = true;
  js::ShellBell bell(spec);
  js::ShellLoads loads;
  loads.damping_per_s = 20.0;
  js::ShellSystem system(bell.body(), loads, [&bell](double t) { bell.actuate(t); });
  jellysim::ode::Leapfrog stepper;
  js::Vector y = system.initial_state(bell.rest_positions()), next;
  const Eigen::Index n = system.position_size();
  write_obj(dir + "/bell_rest.obj", bell, y.head(n));
  const double dt = 1.25e-5, v0 = bell.cavity_volume(y.head(n));
  std::printf("%zu surface vertices, %zu faces; conduction speed %.3f m/s\n", bell.surface().mesh.vertices.size(),
              bell.surface().mesh.triangles.size(), bell.conduction_speed_m_per_s());
  double t = 0.0;
  for (double until : times) {
    for (; t < until - 0.5 * dt; t += dt) {
      stepper.step(system, t, dt, y, next, nullptr);
      y.swap(next);
    }
    const js::Vector x = y.head(n);
    char name[64];
    std::snprintf(name, sizeof name, "/bell_%.3f.obj", until);
    write_obj(dir + name, bell, x);
    std::printf("t = %.3f s: margin displacement near the pacemaker %.3f mm, far side %.3f mm; cavity volume %.4f of rest\n",
                until, 1e3 * js::margin_displacement(bell, x, 0.0), 1e3 * js::margin_displacement(bell, x, std::numbers::pi),
                bell.cavity_volume(x) / v0);
  }
  return 0;
}
