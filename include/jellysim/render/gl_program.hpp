#pragma once
// Compiling and linking GLSL programs in the current OpenGL context: shared by the offscreen
// renderer (EGL) and the real-time viewer (GLFW).
#include <string>

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#ifndef GL_GLCOREARB_PROTOTYPES
#define GL_GLCOREARB_PROTOTYPES
#endif
#include <GL/glcorearb.h>

namespace jellysim::render {

/// Compiles the two shaders and links them into a program; throws RunError with the driver's log.
GLuint link_program(const std::string& vertex_source, const std::string& fragment_source);

/// The meshes' lighting in GLSL (docs/rendering.md): `vec4 shade(vec3 n, vec3 v)` for a unit normal
/// facing the viewer and the unit direction to the eye — ambient, two directional lights (Lambert +
/// Blinn–Phong), a rim that brightens and thickens grazing parts, gamma-encoded — and `through`, what
/// the surface lets through of the light behind it per channel: its uncovered part (1 − α) times the
/// tissue's transmission and Beer–Lambert absorption over d = ½ thickness / |n·v|. Its uniforms: base (RGBA, linear), eye, light_direction[2],
/// light_colour[2], ambient, specular, shininess, rim, rim_colour, transmission, absorption,
/// half_thickness. The offscreen renderer's programs and the viewer's 3D panel share it.
inline constexpr const char* kLightingGlsl = R"(
uniform vec4 base;
uniform vec3 eye;
uniform vec3 light_direction[2];
uniform vec3 light_colour[2];
uniform float ambient;
uniform float specular;
uniform float shininess;
uniform float rim;
uniform vec3 rim_colour;
uniform float transmission;
uniform vec3 absorption;
uniform float half_thickness;
vec3 through(vec3 n, vec3 v, float alpha) {
  float d = half_thickness / max(abs(dot(n, v)), 0.1);
  return (1.0 - alpha) * transmission * exp(-absorption * d);
}
vec4 shade(vec3 n, vec3 v) {
  vec3 c = ambient * base.rgb;
  for (int i = 0; i < 2; ++i) {
    vec3 l = normalize(light_direction[i]);
    vec3 h = normalize(l + v);
    c += light_colour[i] * (max(dot(n, l), 0.0) * base.rgb + specular * pow(max(dot(n, h), 0.0), shininess));
  }
  float grazing = pow(1.0 - abs(dot(n, v)), 2.0);
  c += rim * grazing * rim_colour;
  return vec4(pow(max(c, vec3(0.0)), vec3(1.0 / 2.2)), clamp(base.a + rim * grazing, 0.0, 1.0));
}
)";

}  // namespace jellysim::render
