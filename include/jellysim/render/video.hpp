#pragma once
// MP4 (H.264) through the ffmpeg program: raw RGB frames are piped to its standard input.
#include <cstdio>
#include <filesystem>
#include <string>

#include "jellysim/render/image.hpp"

namespace jellysim::render {

/// Full path of the ffmpeg program on PATH, or empty when there is none.
std::string find_ffmpeg();

class Mp4Writer {
 public:
  /// Starts `ffmpeg` writing `path` (libx264, yuv420p, odd sizes padded to even, constant quality
  /// crf 20, bit-exact flags so the same frames give the same file). Throws RunError when ffmpeg
  /// is missing (install the Debian package ffmpeg) and InputError for fps outside (0, 240].
  Mp4Writer(const std::filesystem::path& path, int width_px, int height_px, double fps);
  ~Mp4Writer();  ///< aborts an unfinished video (closes the pipe, removes the partial file)
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  /// Appends a frame of the size given at construction; throws RunError when ffmpeg has failed.
  void add(const RgbImage& frame);
  /// Waits for ffmpeg; throws RunError (with ffmpeg's last messages) when it failed.
  void finish();
  int frames() const { return frames_; }

 private:
  std::filesystem::path path_, log_;
  int width_, height_;
  int frames_ = 0;
  FILE* pipe_ = nullptr;
};

}  // namespace jellysim::render
