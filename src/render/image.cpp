#include "jellysim/render/image.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>

// stb_easy_font is a single header of static functions; its unused helper would warn.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::render {

RgbImage::RgbImage(int w, int h, Rgb fill) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3) {
  for (std::size_t i = 0; i < pixels.size(); i += 3) std::copy(fill.begin(), fill.end(), pixels.begin() + static_cast<long>(i));
}

Rgb RgbImage::at(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  return {pixels[i], pixels[i + 1], pixels[i + 2]};
}

void RgbImage::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  std::copy(c.begin(), c.end(), pixels.begin() + static_cast<long>(i));
}

void RgbImage::blend(int x, int y, Rgb c, double a) {
  if (x < 0 || y < 0 || x >= width || y >= height || a <= 0.0) return;
  a = std::min(a, 1.0);
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  for (int k = 0; k < 3; ++k) {
    const double v = pixels[i + k] * (1.0 - a) + c[static_cast<std::size_t>(k)] * a;
    pixels[i + k] = static_cast<std::uint8_t>(std::lround(v));
  }
}

namespace {

/// Encodes 8-bit pixels of libpng's simplified `format` (PNG_FORMAT_RGB or _RGBA; 8-bit alpha is
/// straight) once, into a buffer of libpng's bound: asking for the size first would encode twice.
/// (Its PNG_IMAGE_FLAG_FAST saved 1 ms of a frame's 17 and made the frames 40 % larger: not taken.)
std::string encode_png(int width, int height, png_uint_32 format, const std::uint8_t* pixels, int channels) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = format;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, pixels, width * channels, nullptr))
    throw RunError(std::string("cannot encode a PNG: ") + png.message);
  bytes.resize(size);
  return bytes;
}

/// Reads a PNG file as 8-bit pixels of `format` into `pixels` (resized); returns width and height.
std::array<int, 2> decode_png(const std::filesystem::path& path, png_uint_32 format, int channels,
                              std::vector<std::uint8_t>& pixels) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw InputError("cannot read PNG '" + path.string() + "': " + png.message);
  png.format = format;
  const int w = static_cast<int>(png.width), h = static_cast<int>(png.height);
  pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(channels), 0);
  if (!png_image_finish_read(&png, nullptr, pixels.data(), w * channels, nullptr))
    throw InputError("cannot read PNG '" + path.string() + "': " + png.message);
  return {w, h};
}

}  // namespace

std::string png_bytes(const RgbImage& image) {
  return encode_png(image.width, image.height, PNG_FORMAT_RGB, image.pixels.data(), 3);
}

std::string png_bytes(const RgbaImage& image) {
  return encode_png(image.width, image.height, PNG_FORMAT_RGBA, image.pixels.data(), 4);
}

std::array<std::uint8_t, 4> RgbaImage::at(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
  return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
}

void write_png(const RgbImage& image, const std::filesystem::path& path) { io::write_file(path, png_bytes(image)); }

namespace {

template <class Image>
Image read_png_as(const std::filesystem::path& path, png_uint_32 format, int channels) {
  Image image;
  const auto [w, h] = decode_png(path, format, channels, image.pixels);
  image.width = w;
  image.height = h;
  return image;
}

}  // namespace

RgbImage read_png(const std::filesystem::path& path) { return read_png_as<RgbImage>(path, PNG_FORMAT_RGB, 3); }

RgbaImage read_png_rgba(const std::filesystem::path& path) { return read_png_as<RgbaImage>(path, PNG_FORMAT_RGBA, 4); }

ImageDifference compare_images(const RgbImage& a, const RgbImage& b) {
  if (a.width != b.width || a.height != b.height) throw InputError("images differ in size");
  ImageDifference d;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const int diff = std::abs(static_cast<int>(a.pixels[i]) - static_cast<int>(b.pixels[i]));
    sum += diff;
    d.max_abs = std::max(d.max_abs, diff);
  }
  d.mean_abs = a.pixels.empty() ? 0.0 : sum / static_cast<double>(a.pixels.size());
  return d;
}

void draw_segment(RgbImage& image, double x0, double y0, double x1, double y1, double width_px, Rgb colour) {
  const double half = 0.5 * width_px;
  const int xa = static_cast<int>(std::floor(std::min(x0, x1) - half - 1)), xb = static_cast<int>(std::ceil(std::max(x0, x1) + half + 1));
  const int ya = static_cast<int>(std::floor(std::min(y0, y1) - half - 1)), yb = static_cast<int>(std::ceil(std::max(y0, y1) + half + 1));
  const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
  for (int y = std::max(ya, 0); y <= std::min(yb, image.height - 1); ++y) {
    for (int x = std::max(xa, 0); x <= std::min(xb, image.width - 1); ++x) {
      const double px = x + 0.5 - x0, py = y + 0.5 - y0;
      const double t = len2 > 0.0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
      const double dist = std::hypot(px - t * dx, py - t * dy);
      image.blend(x, y, colour, std::clamp(half + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void draw_disc(RgbImage& image, double cx, double cy, double radius_px, Rgb colour) {
  draw_segment(image, cx, cy, cx, cy, 2.0 * radius_px, colour);
}

void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale, Rgb colour) {
  std::vector<char> buffer(text.size() * 300 + 1000);  // ~270 bytes per character at most
  std::string copy = text;
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(), static_cast<int>(buffer.size()));
  const auto* v = reinterpret_cast<const float*>(buffer.data());  // 4 vertices × (x, y, z, rgba) per quad
  for (int q = 0; q < quads; ++q) {
    const float* quad = v + q * 16;
    const int qx0 = static_cast<int>(quad[0]), qy0 = static_cast<int>(quad[1]);
    const int qx1 = static_cast<int>(quad[8]), qy1 = static_cast<int>(quad[9]);
    for (int py = qy0 * scale; py < qy1 * scale; ++py)
      for (int px = qx0 * scale; px < qx1 * scale; ++px) image.set(x + px, y + py, colour);
  }
}

void paste(RgbImage& dst, const RgbImage& src, int x, int y) {
  for (int sy = 0; sy < src.height; ++sy)
    for (int sx = 0; sx < src.width; ++sx) dst.set(x + sx, y + sy, src.at(sx, sy));
}

}  // namespace jellysim::render
