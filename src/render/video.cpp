#include "jellysim/render/video.hpp"

#include <sys/wait.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::render {
namespace {

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string tail_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  return text.size() > 600 ? text.substr(text.size() - 600) : text;
}

}  // namespace

std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/bin:/bin";
  while (!rest.empty()) {
    const std::size_t colon = rest.find(':');
    const std::filesystem::path dir(std::string(rest.substr(0, colon)));
    rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    const auto candidate = dir / "ffmpeg";
    std::error_code ec;
    if (!dir.empty() && std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
  }
  return {};
}

Mp4Writer::Mp4Writer(const std::filesystem::path& path, int width_px, int height_px, double fps)
    : path_(path), log_(path.string() + ".ffmpeg-log"), width_(width_px), height_(height_px) {
  if (!(fps > 0.0 && fps <= 240.0)) throw InputError("video fps = " + io::format_double(fps) + " is out of range (0, 240]");
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty()) throw RunError("ffmpeg is not on PATH: install the Debian package ffmpeg to write MP4 video");
  const std::string command =
      quoted(ffmpeg) + " -nostdin -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " + std::to_string(width_px) + "x" +
      std::to_string(height_px) + " -framerate " + io::format_double(fps) +
      " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -preset medium -crf 20 -pix_fmt yuv420p"
      " -threads 1 -fflags +bitexact -flags:v +bitexact -map_metadata -1 -movflags +faststart -f mp4 " +
      quoted(path.string()) + " 2> " + quoted(log_.string());
  // A broken pipe must surface as an error from fwrite, not kill the process.
  std::signal(SIGPIPE, SIG_IGN);
  pipe_ = ::popen(command.c_str(), "w");
  if (!pipe_) throw RunError("cannot start ffmpeg");
}

Mp4Writer::~Mp4Writer() {
  if (!pipe_) return;
  ::pclose(pipe_);
  std::error_code ec;
  std::filesystem::remove(path_, ec);
  std::filesystem::remove(log_, ec);
}

void Mp4Writer::add(const RgbImage& frame) {
  if (!pipe_) throw RunError("video already finished");
  if (frame.width != width_ || frame.height != height_) throw RunError("video frame size changed");
  if (std::fwrite(frame.pixels.data(), 1, frame.pixels.size(), pipe_) != frame.pixels.size())
    throw RunError("ffmpeg stopped accepting frames: " + tail_of(log_));
  ++frames_;
}

void Mp4Writer::finish() {
  if (!pipe_) return;
  const int status = ::pclose(pipe_);
  pipe_ = nullptr;
  const std::string messages = tail_of(log_);
  std::error_code ec;
  std::filesystem::remove(log_, ec);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::filesystem::remove(path_, ec);
    throw RunError("ffmpeg failed writing '" + path_.string() + "': " + messages);
  }
}

}  // namespace jellysim::render
