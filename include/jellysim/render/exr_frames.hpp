#pragma once
// OpenEXR frames for compositing (Debian's libopenexr-dev, its C++ API): one single-part file per
// frame with named channels in layers, as Nuke and Blender's compositor read them:
//   R, G, B, A   beauty, linear light, premultiplied by A (half float)
//   Z            depth: metres from the camera along its view axis (float; kBackgroundDepth where
//                no surface is)
//   velocity.X, velocity.Y  screen-space motion since the previous frame, pixels per frame, x to the
//                right, y up (float; 0 on the background and at the first frame)
#include <string>

#include "jellysim/render/gl_renderer.hpp"
#include "jellysim/render/image.hpp"

namespace jellysim::render {

/// The beauty's channel value in linear light: the 8-bit gamma-encoded (1/2.2) straight colour
/// `encoded` of a pixel with 8-bit alpha `alpha`, decoded and premultiplied.
float linear_premultiplied(std::uint8_t encoded, std::uint8_t alpha);

/// The bytes of the frame's EXR file (ZIP-compressed scanlines; deterministic). `beauty` and
/// `passes` must have the same size (InputError otherwise); RunError when OpenEXR fails.
std::string exr_bytes(const RgbaImage& beauty, const FramePasses& passes);

}  // namespace jellysim::render
