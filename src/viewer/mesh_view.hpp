#pragma once
// The 3D panel: jellyfish meshes (geometry::Mesh, one per jellyfish) drawn with OpenGL 3.3 core
// into an offscreen colour target with the three-term lighting model (ambient, Lambert diffuse,
// Blinn–Phong specular) and one directional light; translucent umbrellas over opaque tentacles.
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "gl.hpp"

namespace jellysim::viewer {

/// Orbit camera around the meshes' common centre.
struct OrbitCamera {
  double azimuth_deg = 25.0;    ///< around the vertical, from the slice normal (+z)
  double elevation_deg = 15.0;  ///< above the horizontal
  double zoom = 1.0;            ///< > 1: closer
};

class MeshView {
 public:
  MeshView();
  ~MeshView();
  MeshView(const MeshView&) = delete;
  MeshView& operator=(const MeshView&) = delete;

  /// Renders the meshes into a width × height texture (returned) framed to fit all of them, with
  /// `obstacles` (part "obstacles", opaque; not framed) drawn first when given.
  GLuint draw(const std::vector<const geometry::Mesh*>& meshes, const OrbitCamera& camera, int width, int height,
              const geometry::Mesh* obstacles = nullptr, const geometry::Mesh* snow = nullptr);
  /// Samples per pixel the panel is drawn with (0 before the first draw).
  int samples() const { return target_.samples(); }

 private:
  void upload(const geometry::Mesh& mesh);
  void draw_part(const geometry::Mesh& mesh, const char* part, const float rgba[4]);

  GLuint program_ = 0, vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
  GLint u_view_projection_ = -1, u_eye_ = -1, u_colour_ = -1;
  gl::RenderTarget target_;
  std::vector<float> vertex_scratch_;
};

}  // namespace jellysim::viewer
