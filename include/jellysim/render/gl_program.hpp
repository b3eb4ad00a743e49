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

}  // namespace jellysim::render
