#include "recorder.hpp"

#include <cstdio>

#include "jellysim/core/errors.hpp"

namespace jellysim::viewer {

namespace {

std::filesystem::path numbered(const std::filesystem::path& dir, const std::string& prefix, int n, int digits) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%0*d.png", prefix.c_str(), digits, n);
  return dir / name;
}

void make_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw RunError("viewer: cannot create " + dir.string() + ": " + ec.message());
}

}  // namespace

void Recorder::start(const std::filesystem::path& dir, int width, int height, double fps, bool png, bool mp4) {
  stop();
  make_dir(dir);
  dir_ = dir;
  width_ = width;
  height_ = height;
  png_ = png;
  frames_ = 0;
  if (mp4) video_ = std::make_unique<render::Mp4Writer>(dir / "view.mp4", width, height, fps);
  active_ = true;
}

bool Recorder::add(const render::RgbImage& frame, std::string* why) {
  if (!active_) return false;
  if (frame.width != width_ || frame.height != height_) {
    if (why) *why = "the window size changed: recording stopped";
    stop();
    return false;
  }
  if (png_) render::write_png(frame, numbered(dir_, "frame", frames_, 5));
  if (video_) video_->add(frame);
  ++frames_;
  return true;
}

void Recorder::stop() {
  if (video_) {
    if (video_->frames() > 0) video_->finish();
    video_.reset();
  }
  active_ = false;
}

std::filesystem::path next_screenshot_path(const std::filesystem::path& dir, const std::string& prefix) {
  make_dir(dir);
  for (int n = 0;; ++n) {
    const auto path = numbered(dir, prefix, n, 4);
    if (!std::filesystem::exists(path)) return path;
  }
}

std::string keep_frame(const render::RgbImage& frame, Recorder& recorder, bool screenshot,
                       const std::filesystem::path& record_dir) {
  std::string message;  // why the recording stopped, if it did
  if (!recorder.active() || recorder.add(frame, &message)) message.clear();
  if (screenshot) {
    const auto dir = record_dir.empty() ? std::filesystem::path("out/view") : record_dir;
    const auto path = next_screenshot_path(dir, "screenshot");
    render::write_png(frame, path);
    message = "saved " + path.string();
  }
  return message;
}

}  // namespace jellysim::viewer
