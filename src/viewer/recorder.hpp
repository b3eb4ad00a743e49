#pragma once
// Recording what is on screen: every frame as PNG (frame_00000.png …) and into an MP4 through
// ffmpeg (render::Mp4Writer), plus single screenshots.
#include <filesystem>
#include <memory>
#include <string>

#include "jellysim/render/image.hpp"
#include "jellysim/render/video.hpp"

namespace jellysim::viewer {

class Recorder {
 public:
  /// Starts recording into `dir` (created); `png`, `mp4` choose the outputs. Throws RunError when
  /// the directory cannot be made or ffmpeg is missing.
  void start(const std::filesystem::path& dir, int width, int height, double fps, bool png, bool mp4);
  /// Adds a frame; a frame of another size stops the recording (returns false and says why).
  bool add(const render::RgbImage& frame, std::string* why);
  /// Finishes the MP4 (waits for ffmpeg).
  void stop();
  bool active() const { return active_; }
  int frames() const { return frames_; }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::unique_ptr<render::Mp4Writer> video_;
  bool png_ = true;
  bool active_ = false;
  int width_ = 0, height_ = 0, frames_ = 0;
};

/// The next free name `prefix_NNNN.png` in `dir` (created).
std::filesystem::path next_screenshot_path(const std::filesystem::path& dir, const std::string& prefix);

/// The frame just read back from the window: added to the recording when one runs, and written as
/// the next screenshot_NNNN.png in `record_dir` (out/view when empty) when `screenshot`. Returns the
/// message for the panel ("" when there is none).
std::string keep_frame(const render::RgbImage& frame, Recorder& recorder, bool screenshot,
                       const std::filesystem::path& record_dir);

}  // namespace jellysim::viewer
