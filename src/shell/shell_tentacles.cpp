// The bell's tentacles as rods (docs/three-d.md, "Part 3"): stretching and bending chains hanging
// from margin vertices, with the slice's tentacle curtain shared among them.
#include <cmath>
#include <numbers>

#include "jellysim/shell/shell_bell.hpp"

namespace jellysim::shell {

namespace {

/// The point of ring `j` at azimuth φ, as two vertices and their weights (linear along the ring).
RodJoint joint_from_ring(const Rings& rings, std::size_t j, double phi) {
  const double n = rings.count[j];
  double u = phi / (2.0 * std::numbers::pi) * n - rings.offset[j];
  u -= n * std::floor(u / n);
  const int i0 = static_cast<int>(std::floor(u)) % rings.count[j];
  const double w = u - std::floor(u);
  RodJoint joint;
  joint.a = {rings.first[j] + i0, rings.first[j] + (i0 + 1) % rings.count[j]};
  joint.a_weights = {1.0 - w, w};
  return joint;
}

}  // namespace

void ShellBell::build_tentacles() {
  const int n = spec_.tentacle_count;
  const double length = spec_.slice.tentacle_length_m;
  const Rings& rings = surface_.rings;
  if (n == 0 || !(length > 0) || rings.first.size() < 2) return;
  // Each rod carries the slice's curtain over its share w of the margin (EA = S_t w, EI = B_t w).
  const double share = std::numbers::pi * spec_.slice.diameter_m / n;
  const jellyfish::ContinuumMaterial& c = spec_.slice.material;
  const double ea = c.tentacle_stretching_n_per_m * share, ei = c.tentacle_bending_n_m * share;
  const double line_density = c.tentacle_line_density_kg_per_m2 * share;
  const int segments = std::max(2, static_cast<int>(std::ceil(length / spec_.target_edge_m)));
  const double l = length / segments;
  const std::size_t margin = rings.first.size() - 1;
  for (int k = 0; k < n; ++k) {
    const int root = rings.first[margin] + static_cast<int>(std::lround(static_cast<double>(k) * rings.count[margin] / n)) % rings.count[margin];
    const Vec3 x_root = vertex(rest_, root);
    RodJoint joint = joint_from_ring(rings, margin - 1, std::atan2(x_root.z(), x_root.x()));
    const Vec3 above = joint.a_weights[0] * vertex(rest_, joint.a[0]) + joint.a_weights[1] * vertex(rest_, joint.a[1]);
    const Vec3 down = (x_root - above).normalized();  // continuing the meridian: a straight rod at rest
    std::vector<int> strand{root};
    body_.mass_kg[static_cast<std::size_t>(root)] += 0.5 * line_density * l;
    for (int s = 1; s <= segments; ++s) {
      const Vec3 p = x_root + (s * l) * down;
      rest_.conservativeResize(rest_.size() + 3);
      rest_.tail<3>() = p;
      body_.mass_kg.push_back(line_density * (s < segments ? l : 0.5 * l));
      strand.push_back(static_cast<int>(body_.mass_kg.size()) - 1);
      body_.rod_segments.push_back({strand[strand.size() - 2], strand.back(), ea, l});
    }
    // The root joint bends the rod's first half segment (2EI/l), the others a whole one (EI/l).
    joint.b = root;
    joint.c = strand[1];
    joint.stiffness_n_m = 2.0 * ei / l;
    body_.rod_joints.push_back(joint);
    for (std::size_t s = 1; s + 1 < strand.size(); ++s)
      body_.rod_joints.push_back({{strand[s - 1], strand[s - 1]}, {1.0, 0.0}, strand[s], strand[s + 1], ei / l});
    tentacles_.push_back(strand);
  }
}

}  // namespace jellysim::shell
