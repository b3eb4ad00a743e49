// The shell bell swimming in 3D water (docs/three-d.md, "Part 4"), for measurements from the
// command line: a tank of free-slip walls four bell diameters wide and deep and five tall, solved on
// its quarter (symmetric stroke) or half (pacemaker on the +x side), printing each frame's figures,
// the swimming summary and the wall-clock split per step:
//   swim_3d CELLS_ACROSS_BELL CYCLES [pacemaker] [threads=N] [fpc=N] [dt=S] [edge=F] [tall=N]
//          [conduction=M_PER_S] [no-tentacles]
// edge: the shell's edge length in fluid cells (default 0.5: Peskin's rule, which the slice's
// markers follow too); tall: the tank's height in bell diameters (default 5; the aperture starts
// 1.25 diameters above the floor); conduction: the pacemaker's impulse's speed around the margin
// (default: the slice's, meridian arc / neural delay). Pictures of the simulated surface:
// `jellysim run scenes/jellyfish-3d.toml` (docs/three-d.md).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "jellysim/swim3d/swimmer_3d.hpp"

namespace s3 = jellysim::swim3d;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: swim_3d CELLS_ACROSS_BELL CYCLES [pacemaker] [threads=N] [fpc=N] [dt=S] [edge=F] [tall=N] [conduction=M_PER_S] [no-tentacles]\n");
    return 2;
  }
  const int across = std::atoi(argv[1]);
  const int cycles = std::atoi(argv[2]);
  s3::Swim3dSpec spec;
  double edge_cells = 0.5;
  int tall = 5;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "pacemaker") spec.bell.pacemaker = true;
    else if (arg.rfind("threads=", 0) == 0) spec.threads = std::atoi(arg.c_str() + 8);
    else if (arg.rfind("fpc=", 0) == 0) spec.frames_per_cycle = std::atoi(arg.c_str() + 4);
    else if (arg.rfind("dt=", 0) == 0) spec.max_time_step_s = std::atof(arg.c_str() + 3);
    else if (arg.rfind("edge=", 0) == 0) edge_cells = std::atof(arg.c_str() + 5);
    else if (arg.rfind("tall=", 0) == 0) tall = std::atoi(arg.c_str() + 5);
    else if (arg == "no-tentacles") spec.bell.slice.tentacle_length_m = 0.0, spec.bell.tentacle_count = 0;
    else if (arg.rfind("conduction=", 0) == 0) spec.bell.conduction_speed_m_per_s = std::atof(arg.c_str() + 11);
    else {
      std::fprintf(stderr, "swim_3d: unknown argument '%s'\n", arg.c_str());
      return 2;
    }
  }
  if (across < 4 || across > 256 || cycles < 1 || cycles > 100 || tall < 3 || tall > 50) {
    std::fprintf(stderr, "swim_3d: CELLS_ACROSS_BELL in [4, 256], CYCLES in [1, 100], tall in [3, 50]\n");
    return 2;
  }
  const double D = spec.bell.slice.diameter_m, h = D / across;
  spec.tank_size_m = {4 * D, tall * D, 4 * D};
  spec.cells = {4 * across, tall * across, 4 * across};
  spec.aperture_height_m = 1.25 * D;
  spec.bell.target_edge_m = edge_cells * h;
  try {
    s3::Swimmer3d swimmer(spec);
    const auto g = s3::solved_grid(spec);
    std::printf("# %s tank: %d x %d x %d cells solved, h = %.3f mm, %zu markers\n",
                std::string(s3::to_string(s3::resolved_symmetry(spec))).c_str(), g.n(0), g.n(1), g.n(2), 1e3 * h,
                swimmer.markers().size());
    std::printf("# t_s y_mm x_mm vy_mm_s volume_ml heading_deg tilt_deg krylov\n");
    std::vector<s3::Frame3d> frames{swimmer.frame()};
    for (int k = 0; k < cycles * spec.frames_per_cycle; ++k) {
      frames.push_back(swimmer.advance_frame());
      const s3::Frame3d& f = frames.back();
      std::printf("%.4f %.3f %.4f %.2f %.3f %.3f %.3f %d\n", f.time_s, 1e3 * f.centroid[1], 1e3 * f.centroid[0],
                  1e3 * f.velocity[1], 1e6 * f.cavity_volume_m3, f.heading_deg, f.tilt_deg, f.krylov_iterations);
      std::fflush(stdout);
    }
    const s3::SwimSummary3d s = s3::summarize(frames, spec.frames_per_cycle);
    std::printf("# cycles (mm):");
    for (double d : s.cycle_distance_m) std::printf(" %.3f", 1e3 * d);
    std::printf("\n# heading change per cycle (deg):");
    for (double d : s.cycle_heading_deg) std::printf(" %.3f", d);
    const s3::Swim3dTimings& t = swimmer.timings();
    std::printf("\n# distance per cycle %.3f mm, first cycle %.3f mm, heading change %.3f deg/cycle, tilt %.3f deg\n",
                1e3 * s.distance_per_cycle_m, 1e3 * s.first_cycle_m, s.heading_change_deg_per_cycle, s.final_tilt_deg);
    std::printf("# %d steps, %.1f ms per step: transfer %.1f, fluid %.1f, krylov %.1f; %.1f GMRES iterations per step; %.4fx real time\n",
                t.steps, 1e3 * t.total_s / t.steps, 1e3 * t.transfer_s / t.steps, 1e3 * t.fluid_s / t.steps,
                1e3 * t.krylov_s / t.steps, static_cast<double>(t.krylov_iterations) / t.steps, swimmer.time_s() / t.total_s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swim_3d: %s\n", e.what());
    return 2;
  }
  return 0;
}
