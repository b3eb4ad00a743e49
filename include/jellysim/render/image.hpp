#pragma once
// 8-bit RGB images in memory: PNG files (libpng), simple anti-aliased 2D drawing and text labels
// (stb_easy_font) for composing pictures such as the Figure 8.19 stages.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace jellysim::render {

using Rgb = std::array<std::uint8_t, 3>;

/// Row-major, top row first, 3 bytes per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  RgbImage() = default;
  RgbImage(int w, int h, Rgb fill = {0, 0, 0});
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb c);
  /// Blends `c` over the pixel with coverage a ∈ [0, 1].
  void blend(int x, int y, Rgb c, double a);
};

/// Row-major, top row first, 4 bytes per pixel: R, G, B and straight (not premultiplied) alpha.
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
  std::array<std::uint8_t, 4> at(int x, int y) const;
};

/// The bytes of an RGBA PNG file of the image (libpng); throws RunError when libpng fails.
std::string png_bytes(const RgbaImage& image);
/// Reads an 8-bit PNG with its alpha (255 where the file has none); InputError when unreadable.
RgbaImage read_png_rgba(const std::filesystem::path& path);

/// The bytes of a PNG file of the image (libpng); throws RunError when libpng fails.
std::string png_bytes(const RgbImage& image);
/// Writes png_bytes to a file (io::write_file); throws RunError when it cannot.
void write_png(const RgbImage& image, const std::filesystem::path& path);
/// Reads an 8-bit RGB(A) PNG (alpha dropped); throws InputError for an unreadable file.
RgbImage read_png(const std::filesystem::path& path);

/// Mean absolute difference per channel (0–255) and the largest one; sizes must match.
struct ImageDifference {
  double mean_abs = 0.0;
  int max_abs = 0;
};
ImageDifference compare_images(const RgbImage& a, const RgbImage& b);

/// Anti-aliased segment of the given width in pixels (coordinates in pixels, y down).
void draw_segment(RgbImage& image, double x0, double y0, double x1, double y1, double width_px, Rgb colour);
/// Filled anti-aliased disc.
void draw_disc(RgbImage& image, double cx, double cy, double radius_px, Rgb colour);
/// Text with stb_easy_font's built-in font, scaled by an integer factor; top-left at (x, y).
void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale, Rgb colour);
/// Copies `src` into `dst` with its top-left corner at (x, y) (clipped).
void paste(RgbImage& dst, const RgbImage& src, int x, int y);

}  // namespace jellysim::render
