#include "jellysim/render/exr_frames.hpp"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <half.h>

#include <array>
#include <cmath>
#include <exception>
#include <sstream>
#include <vector>

#include "jellysim/core/errors.hpp"

namespace jellysim::render {

float linear_premultiplied(std::uint8_t encoded, std::uint8_t alpha) {
  return static_cast<float>(std::pow(encoded / 255.0, 2.2) * (alpha / 255.0));
}

namespace {

/// The beauty as four half-float planes (R, G, B, A), linear and premultiplied.
std::array<std::vector<half>, 4> beauty_planes(const RgbaImage& image) {
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::array<std::vector<half>, 4> planes;
  for (auto& p : planes) p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* px = image.pixels.data() + 4 * i;
    for (std::size_t k = 0; k < 3; ++k) planes[k][i] = half(linear_premultiplied(px[k], px[3]));
    planes[3][i] = half(static_cast<float>(px[3] / 255.0));
  }
  return planes;
}

}  // namespace

std::string exr_bytes(const RgbaImage& beauty, const FramePasses& passes) {
  if (beauty.width != passes.width || beauty.height != passes.height)
    throw InputError("the EXR frame's beauty and passes differ in size");
  const auto planes = beauty_planes(beauty);
  const std::size_t w = static_cast<std::size_t>(beauty.width);
  try {
    Imf::Header header(beauty.width, beauty.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const char* beauty_names[4] = {"R", "G", "B", "A"};
    for (std::size_t k = 0; k < 4; ++k) {
      header.channels().insert(beauty_names[k], Imf::Channel(Imf::HALF));
      frame.insert(beauty_names[k], Imf::Slice(Imf::HALF, const_cast<char*>(reinterpret_cast<const char*>(planes[k].data())),
                                               sizeof(half), sizeof(half) * w));
    }
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    frame.insert("Z", Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(passes.depth_m.data())),
                                 sizeof(float), sizeof(float) * w));
    const char* velocity_names[2] = {"velocity.X", "velocity.Y"};
    for (std::size_t k = 0; k < 2; ++k) {
      header.channels().insert(velocity_names[k], Imf::Channel(Imf::FLOAT));
      char* base = const_cast<char*>(reinterpret_cast<const char*>(passes.velocity_px.data() + k));
      frame.insert(velocity_names[k], Imf::Slice(Imf::FLOAT, base, 2 * sizeof(float), 2 * sizeof(float) * w));
    }
    Imf::StdOSStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(beauty.height);
    }
    return stream.str();
  } catch (const std::exception& e) {
    throw RunError(std::string("cannot encode an OpenEXR frame: ") + e.what());
  }
}

}  // namespace jellysim::render
