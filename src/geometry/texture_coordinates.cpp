#include "jellysim/geometry/texture_coordinates.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

/// The umbrella's rows: the exumbrellar apex (v = 0), rings to the margin (v = 1), the
/// subumbrellar rings from the margin (v = 1) back up to its apex (v = 0).
void umbrella_coordinates(const UmbrellaLayout& L, std::vector<TexCoord>& uv) {
  const int E = L.exumbrella_rings, sub_rows = L.rows - 1 - (E + 1);
  for (int r = 0; r < L.rows; ++r) {
    const double v = r <= E ? static_cast<double>(r) / E : static_cast<double>(L.rows - 1 - r) / sub_rows;
    const bool pole = r == 0 || r == L.rows - 1;
    for (int j = 0; j < (pole ? 1 : L.disc_points); ++j)
      uv[L.vertex(r, j)] = {pole ? 0.5f : static_cast<float>(static_cast<double>(j) / L.disc_points),
                            static_cast<float>(v)};
  }
}

}  // namespace

std::vector<TexCoord> texture_coordinates(const FrameGeometry& g) {
  std::vector<TexCoord> uv(g.mesh.vertex_count());
  const std::uint32_t umbrella = umbrella_vertex_count(g);
  if (g.umbrella_uv.empty()) umbrella_coordinates(g.umbrella, uv);
  else if (g.umbrella_uv.size() == umbrella) std::copy(g.umbrella_uv.begin(), g.umbrella_uv.end(), uv.begin());
  else throw InputError("texture coordinates: the umbrella has " + std::to_string(umbrella) + " vertices but " +
                        std::to_string(g.umbrella_uv.size()) + " coordinates");
  std::size_t samples = 0;
  for (const auto& line : g.tentacle_lines) samples += line.size();
  const std::size_t tube_vertices = uv.size() - umbrella;
  if (samples == 0 && tube_vertices == 0) return uv;  // a bell without tentacles
  if (samples == 0 || tube_vertices % samples != 0)
    throw InputError("texture coordinates: the tentacle tubes do not match their lines");
  const std::size_t sides = tube_vertices / samples;
  std::size_t at = umbrella;
  for (const auto& line : g.tentacle_lines)
    for (std::size_t m = 0; m < line.size(); ++m)
      for (std::size_t s = 0; s < sides; ++s)
        uv[at++] = {static_cast<float>(static_cast<double>(s) / static_cast<double>(sides)),
                    static_cast<float>(static_cast<double>(m) / static_cast<double>(line.size() - 1))};
  return uv;
}

SeamSplit split_u_seam(const std::vector<TexCoord>& uv, const std::vector<std::uint32_t>& indices,
                       std::uint32_t first_index, std::uint32_t index_count) {
  SeamSplit split{uv, {}, {}};
  split.corners.reserve(index_count);
  std::map<std::uint32_t, std::uint32_t> duplicate_of;  // vertex → its entry with u + 1
  for (std::uint32_t k = first_index; k < first_index + index_count; k += 3) {
    const std::uint32_t* t = indices.data() + k;
    const auto [lo, hi] = std::minmax({uv[t[0]][0], uv[t[1]][0], uv[t[2]][0]});
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = t[c];
      if (hi - lo <= 0.5f || uv[v][0] >= 0.5f) {
        split.corners.push_back(v);
        continue;
      }
      auto [it, added] = duplicate_of.try_emplace(v, static_cast<std::uint32_t>(split.uv.size()));
      if (added) {
        split.uv.push_back({uv[v][0] + 1.0f, uv[v][1]});
        split.duplicated.push_back(v);
      }
      split.corners.push_back(it->second);
    }
  }
  return split;
}

}  // namespace jellysim::geometry
