#include "jellysim/render/video.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <vector>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

extern char** environ;

namespace jellysim::render {
namespace {

/// ffmpeg's arguments: raw RGB frames on its standard input, an H.264 MP4 written to `output`.
std::vector<std::string> ffmpeg_arguments(const std::string& ffmpeg, int width_px, int height_px, double fps,
                                          const std::string& output) {
  return {ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
          std::to_string(width_px) + "x" + std::to_string(height_px), "-framerate", io::format_double(fps), "-i", "-",
          "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset", "medium", "-crf", "20", "-pix_fmt",
          "yuv420p", "-threads", "1", "-fflags", "+bitexact", "-flags:v", "+bitexact", "-map_metadata", "-1",
          "-movflags", "+faststart", "-f", "mp4", output};
}

/// A copy of `fd` numbered above the standard streams and fd 3, so that the child's dup2s to 0-3
/// cannot overwrite one another's source; close-on-exec.
int high_copy(int fd) {
  const int copy = ::fcntl(fd, F_DUPFD_CLOEXEC, 4);
  if (copy < 0) throw RunError("cannot start ffmpeg: " + io::os_reason(errno));
  return copy;
}

/// Starts ffmpeg with `input` as its standard input, `log` as its standard error and `output` as
/// its fd 3, in a process group of its own (a terminal's signals reach jellysim only) and with the
/// default action for the signals jellysim handles or ignores.
pid_t spawn_in_own_group(const std::vector<std::string>& arguments, int input, int log, int output) {
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int sources[3] = {high_copy(input), high_copy(log), high_copy(output)};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sources[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, sources[1], STDERR_FILENO);
  posix_spawn_file_actions_adddup2(&actions, sources[2], 3);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t defaults, none;
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGQUIT}) sigaddset(&defaults, s);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setsigmask(&attributes, &none);
  pid_t pid = -1;
  const int error = ::posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  for (int fd : sources) ::close(fd);
  if (error != 0) throw RunError("cannot start ffmpeg: " + io::os_reason(error));
  return pid;
}

/// How ffmpeg ended, for a message.
std::string ending(int status) {
  if (WIFSIGNALED(status)) return "ffmpeg was killed by signal " + std::to_string(WTERMSIG(status));
  return "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status));
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

Mp4Writer::Mp4Writer(const std::filesystem::path& path, int fd, int width_px, int height_px, double fps)
    : path_(path), width_(width_px), height_(height_px) {
  start(fd, fps);
}

Mp4Writer::Mp4Writer(const std::filesystem::path& path, int width_px, int height_px, double fps)
    : path_(path), width_(width_px), height_(height_px) {
  owned_fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (owned_fd_ < 0) throw RunError("cannot write '" + path.string() + "': " + io::os_reason(errno));
  try {
    start(owned_fd_, fps);
  } catch (...) {
    ::close(owned_fd_);
    ::unlink(path.c_str());
    throw;
  }
}

void Mp4Writer::start(int output_fd, double fps) {
  if (!(fps > 0.0 && fps <= 240.0)) throw InputError("video fps = " + io::format_double(fps) + " is out of range (0, 240]");
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty()) throw RunError("ffmpeg is not on PATH: install the Debian package ffmpeg to write MP4 video");
  // The same open file, reached through ffmpeg's fd 3 (no name in the results directory is
  // opened); by name only where there is no /proc.
  std::error_code ec;
  const std::string output = std::filesystem::is_directory("/proc/self/fd", ec) ? "/proc/self/fd/3" : path_.string();
  // A broken pipe must surface as an error from write, not kill the process.
  std::signal(SIGPIPE, SIG_IGN);
  log_ = ::memfd_create("ffmpeg-log", MFD_CLOEXEC);
  if (log_ < 0) throw RunError("cannot start ffmpeg: " + io::os_reason(errno));
  int pipe_ends[2];
  if (::pipe2(pipe_ends, O_CLOEXEC) != 0) {
    const int error = errno;
    ::close(log_);
    throw RunError("cannot start ffmpeg: " + io::os_reason(error));
  }
  try {
    pid_ = spawn_in_own_group(ffmpeg_arguments(ffmpeg, width_, height_, fps, output), pipe_ends[0], log_, output_fd);
  } catch (...) {
    for (int fd : {pipe_ends[0], pipe_ends[1], log_}) ::close(fd);
    throw;
  }
  ::close(pipe_ends[0]);
  input_ = pipe_ends[1];
}

Mp4Writer::~Mp4Writer() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);  // an abandoned video: no need to let it finish
    wait_encoder();
  }
  if (log_ >= 0) ::close(log_);
  if (owned_fd_ >= 0) {
    ::close(owned_fd_);
    ::unlink(path_.c_str());
  }
}

/// Closes ffmpeg's input (the end of the video) and waits for it: its wait status, or nothing
/// when waiting failed (errno says why).
std::optional<int> Mp4Writer::wait_encoder() {
  if (input_ >= 0) ::close(input_);
  input_ = -1;
  int status = 0;
  pid_t waited;
  while ((waited = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return waited > 0 ? std::optional<int>(status) : std::nullopt;
}

std::string Mp4Writer::messages() const {
  char text[600];
  const off_t size = ::lseek(log_, 0, SEEK_END);
  const off_t from = size > static_cast<off_t>(sizeof text) ? size - static_cast<off_t>(sizeof text) : 0;
  const ssize_t n = size > 0 ? ::pread(log_, text, sizeof text, from) : 0;
  std::string tail(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ')) tail.pop_back();
  return tail;
}

void Mp4Writer::add(const RgbImage& frame) {
  if (pid_ <= 0) throw RunError("video already finished");
  if (frame.width != width_ || frame.height != height_) throw RunError("video frame size changed");
  std::string_view bytes(reinterpret_cast<const char*>(frame.pixels.data()), frame.pixels.size());
  while (!bytes.empty()) {
    const ssize_t n = ::write(input_, bytes.data(), bytes.size());
    if (n < 0) {
      const int error = errno;
      if (error == EINTR) continue;
      const std::string log = messages();
      throw RunError("ffmpeg stopped accepting frames (" + io::os_reason(error) + ")" + (log.empty() ? "" : ": " + log));
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  ++frames_;
}

void Mp4Writer::finish() {
  if (pid_ <= 0) return;
  const std::optional<int> status = wait_encoder();
  const std::string how = status ? ending(*status) : "cannot wait for ffmpeg: " + io::os_reason(errno);
  const std::string log = messages();
  if (!status || !WIFEXITED(*status) || WEXITSTATUS(*status) != 0)
    throw RunError("ffmpeg failed writing '" + path_.string() + "': " + how + (log.empty() ? "" : ": " + log));
  if (owned_fd_ >= 0) ::close(owned_fd_);
  owned_fd_ = -1;
}

}  // namespace jellysim::render
