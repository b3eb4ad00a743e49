#pragma once
// MP4 (H.264) through the ffmpeg program: raw RGB frames are piped to its standard input.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>

#include "jellysim/render/image.hpp"

namespace jellysim::render {

/// Full path of the ffmpeg program on PATH, or empty when there is none.
std::string find_ffmpeg();

class Mp4Writer {
 public:
  /// Starts `ffmpeg` writing the video into `fd`, an open, empty regular file whose name is `path`
  /// (libx264, yuv420p, odd sizes padded to even, constant quality crf 20, bit-exact flags so the
  /// same frames give the same file). ffmpeg reaches the file through the descriptor (its fd 3, by
  /// /proc/self/fd), not by name, and runs in a process group of its own: a terminal's Ctrl-C
  /// reaches jellysim alone, which decides (finish() then encodes the frames so far). The caller
  /// keeps `fd` open until finish() and owns the file. Throws RunError when ffmpeg is missing
  /// (install the Debian package ffmpeg) or cannot start, and InputError for fps outside (0, 240].
  Mp4Writer(const std::filesystem::path& path, int fd, int width_px, int height_px, double fps);
  /// The same into `path`, created or truncated (never through a symlink there); an unfinished
  /// video is removed.
  Mp4Writer(const std::filesystem::path& path, int width_px, int height_px, double fps);
  ~Mp4Writer();  ///< aborts an unfinished video (ffmpeg is stopped)
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  /// Appends a frame of the size given at construction; throws RunError when ffmpeg has failed.
  void add(const RgbImage& frame);
  /// Waits for ffmpeg; throws RunError (how it ended, and its last messages) when it failed.
  void finish();
  int frames() const { return frames_; }

 private:
  void start(int output_fd, double fps);
  std::string messages() const;
  std::optional<int> wait_encoder();

  std::filesystem::path path_;
  int width_, height_;
  int frames_ = 0;
  pid_t pid_ = -1;
  int input_ = -1;     ///< the write end of ffmpeg's standard input
  int log_ = -1;       ///< ffmpeg's standard error: a memory file, never in the results directory
  int owned_fd_ = -1;  ///< the file of the path-only constructor
};

}  // namespace jellysim::render
