#include "jellysim/io/output.hpp"

#include "jellysim/core/errors.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace jellysim::io {

namespace fs = std::filesystem;

std::string os_reason(int error_number) { return std::generic_category().message(error_number); }

namespace {

// Random part of temporary names: unpredictable (a file planted at a guessed name cannot catch a
// write), unique within the process by a counter.
std::string temporary_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  thread_local std::mt19937_64 rng{std::random_device{}()};
  const std::uint64_t n = counter.fetch_add(1) ^ (rng() << 16);
  char buf[24];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, n, 36);
  return "-" + std::string(buf, end);
}

// Closes a descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

/// Throws the RunError of a failed write of `shown`; `error` is the errno of the call that failed,
/// taken right after it (anything called since may have changed errno).
[[noreturn]] void fail_writing(const fs::path& shown, int error) {
  throw RunError("cannot write '" + shown.string() + "': " + os_reason(error));
}

/// fsync and close of a written file; the first that fails throws with its own reason.
void sync_and_close(int& fd, const fs::path& shown) {
  const int synced = ::fsync(fd);
  const int sync_error = errno;
  const int closed = ::close(fd);
  const int close_error = errno;
  fd = -1;
  if (synced != 0) fail_writing(shown, sync_error);
  if (closed != 0 && close_error != EINTR) fail_writing(shown, close_error);
}

/// rename(2) of a written temporary into place; on failure the temporary is removed and the
/// rename's own reason is reported.
void move_into_place(const fs::path& temporary, const fs::path& target) {
  if (::rename(temporary.c_str(), target.c_str()) == 0) return;
  const int error = errno;
  ::unlink(temporary.c_str());
  fail_writing(target, error);
}

}  // namespace

TemporaryFile create_temporary_beside(const fs::path& target) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path path = target;
    path += ".tmp-" + std::to_string(::getpid()) + temporary_suffix();
    // Exclusive: fails on anything already there, a symlink included (never followed).
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return {std::move(path), fd};
    const int error = errno;
    if (error != EEXIST) fail_writing(target, error);
  }
  throw RunError("cannot write '" + target.string() + "': no free temporary name beside it");
}

void write_all(int fd, std::string_view content, const fs::path& shown) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0) {
      const int error = errno;
      if (error == EINTR) continue;
      fail_writing(shown, error);
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
}

void write_file_atomically(const fs::path& target, std::string_view content) {
  TemporaryFile tmp = create_temporary_beside(target);
  try {
    write_all(tmp.fd, content, target);
    sync_and_close(tmp.fd, target);
  } catch (...) {
    if (tmp.fd >= 0) ::close(tmp.fd);
    ::unlink(tmp.path.c_str());
    throw;
  }
  move_into_place(tmp.path, target);
}

void write_file(const fs::path& path, std::string_view content) {
  Descriptor d{::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666)};
  if (d.fd < 0) fail_writing(path, errno);
  write_all(d.fd, content, path);
  const int closed = ::close(d.fd);
  const int error = errno;
  d.fd = -1;
  if (closed != 0 && error != EINTR) fail_writing(path, error);
}

namespace {

/// "regular file", "directory", "named pipe", ... for messages.
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string read_regular_file(const fs::path& path, std::uintmax_t max_bytes, bool follow_links) {
  // O_NONBLOCK: opening a named pipe does not wait for a writer; fstat then refuses it.
  Descriptor d{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | (follow_links ? 0 : O_NOFOLLOW))};
  if (d.fd < 0) {
    if (errno == ELOOP) throw InputError("'" + path.string() + "' is a symbolic link, not a regular file");
    throw InputError("cannot read '" + path.string() + "': " + os_reason(errno));
  }
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) throw InputError("cannot read '" + path.string() + "': " + os_reason(errno));
  if (!S_ISREG(st.st_mode)) throw InputError("'" + path.string() + "' is " + kind_of(st.st_mode) + ", not a regular file");
  const auto bytes = static_cast<std::uintmax_t>(st.st_size);
  if (bytes > max_bytes)
    throw InputError("'" + path.string() + "' is " + std::to_string(bytes) + " bytes; at most " + std::to_string(max_bytes));
  std::string text(static_cast<std::size_t>(bytes), '\0');
  std::size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = ::read(d.fd, text.data() + at, text.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError("cannot read '" + path.string() + "': " + os_reason(errno));
    if (n == 0) break;  // shorter than fstat said: it shrank meanwhile
    at += static_cast<std::size_t>(n);
  }
  text.resize(at);
  return text;
}

class DirectoryLock {
 public:
  DirectoryLock(fs::path file, int fd) : file_(std::move(file)), fd_(fd) {}
  ~DirectoryLock() {
    ::unlink(file_.c_str());  // while still locked: a run waiting on this file then sees it gone (acquire's check)
    ::close(fd_);
  }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  fs::path file_;
  int fd_;
};

namespace {

/// The holder's pid as its lock file says (" (pid N)"), or "".
std::string lock_holder(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string pid = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  const bool digits = !pid.empty() && std::all_of(pid.begin(), pid.end(), [](char c) { return c >= '0' && c <= '9'; });
  return digits ? " (pid " + pid + ")" : "";
}

/// Whether `fd` is still the file at `path` (not one a releasing run unlinked meanwhile).
bool still_linked(int fd, const fs::path& path) {
  struct stat open_file {}, named {};
  return ::fstat(fd, &open_file) == 0 && ::lstat(path.c_str(), &named) == 0 && open_file.st_dev == named.st_dev &&
         open_file.st_ino == named.st_ino;
}

}  // namespace

std::shared_ptr<DirectoryLock> lock_directory(const fs::path& dir, std::string_view option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw RunError("cannot create output directory '" + dir.string() + "': " + ec.message());
  const fs::path file = dir / kLockName;
  for (int attempt = 0; attempt < 100; ++attempt) {
    Descriptor d{::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644)};
    if (d.fd < 0)
      throw InputError(std::string(option) + " '" + dir.string() + "': cannot open its lock file '" + file.string() +
                       "': " + os_reason(errno));
    if (::flock(d.fd, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK) throw RunError("cannot lock '" + file.string() + "': " + os_reason(errno));
      throw InputError(std::string(option) + " '" + dir.string() + "' is in use by another jellysim run" +
                       lock_holder(d.fd) + ", which holds '" + file.string() +
                       "': wait for it to end, or choose another directory");
    }
    if (!still_linked(d.fd, file)) continue;  // released and removed meanwhile: lock the new one
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(d.fd, 0) != 0 || ::pwrite(d.fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size()))
      throw RunError("cannot write '" + file.string() + "': " + os_reason(errno));
    auto lock = std::make_shared<DirectoryLock>(file, d.fd);
    d.fd = -1;
    return lock;
  }
  throw RunError("cannot lock '" + file.string() + "': it keeps being replaced");
}

namespace {

/// 128 random bits as 32 hexadecimal digits.
std::string new_run_id() {
  std::random_device device;
  std::string id;
  for (int k = 0; k < 4; ++k) {
    char buf[9];
    std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(device()));
    id += buf;
  }
  return id;
}

constexpr std::string_view kRunIdOpen = " [run ", kRunIdClose = "]";

}  // namespace

/// The files a run wrote, kept on disk as the list grows, so a killed run still leaves it right.
/// Its first line names the command and, while the run can be resumed, the run's id.
class RunManifest {
 public:
  /// `names`: an earlier run's outputs that this run continues (a resumed run).
  RunManifest(fs::path file, std::string_view command, std::string run_id, std::set<std::string> names = {})
      : file_(std::move(file)), command_(command), run_id_(std::move(run_id)), names_(std::move(names)) {
    write_whole(true);
  }
  void record(const std::string& relative) {
    const std::lock_guard lock(mutex_);
    if (!names_.insert(relative).second) return;
    Descriptor d{::open(file_.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC)};
    if (d.fd < 0) fail_writing(file_, errno);
    write_all(d.fd, relative + '\n', file_);
  }
  void finish(bool keep_run_id) {
    const std::lock_guard lock(mutex_);
    write_whole(keep_run_id);
  }
  void forget(const std::string& relative) {
    const std::lock_guard lock(mutex_);
    if (names_.erase(relative) > 0) write_whole(true);
  }
  const std::string& run_id() const { return run_id_; }

 private:
  void write_whole(bool with_run_id) const {
    std::string text = "# jellysim " + command_ +
                       ": the files of this run; a later run into this directory removes them first" +
                       (with_run_id ? std::string(kRunIdOpen) + run_id_ + std::string(kRunIdClose) : "") + "\n";
    for (const std::string& n : names_) text += n + '\n';
    write_file_atomically(file_, text);
  }

  std::mutex mutex_;
  fs::path file_;
  std::string command_, run_id_;
  std::set<std::string> names_;
};

std::string manifest_run_id(const fs::path& dir) {
  std::ifstream in(dir / kManifestName);
  std::string first;
  if (!std::getline(in, first) || !first.starts_with('#') || !first.ends_with(kRunIdClose)) return "";
  const std::size_t at = first.rfind(kRunIdOpen);
  if (at == std::string::npos) return "";
  const std::size_t from = at + kRunIdOpen.size();
  return first.substr(from, first.size() - kRunIdClose.size() - from);
}

namespace {

/// A temporary of OutputDir (NAME.tmp-PID-RANDOM, or NAME.tmp-PID of earlier versions) that a
/// killed run left behind, or the ffmpeg log that earlier versions kept beside a video's temporary
/// (NAME.tmp-PID-RANDOM.ffmpeg-log).
bool is_leftover_temporary(std::string_view name) {
  constexpr std::string_view kEncoderLog = ".ffmpeg-log";
  if (name.ends_with(kEncoderLog)) name.remove_suffix(kEncoderLog.size());
  const std::size_t at = name.rfind(".tmp-");
  if (at == std::string::npos || at + 5 == name.size()) return false;
  const std::string_view tail = name.substr(at + 5);
  const std::size_t dash = tail.find('-');
  const std::string_view pid = tail.substr(0, dash);
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto base36 = [&](char c) { return digit(c) || (c >= 'a' && c <= 'z'); };
  if (pid.empty() || !std::all_of(pid.begin(), pid.end(), digit)) return false;
  if (dash == std::string_view::npos) return true;
  const std::string_view random = tail.substr(dash + 1);
  return !random.empty() && std::all_of(random.begin(), random.end(), base36);
}

/// The relative paths an earlier run's manifest lists (none when there is no manifest).
std::set<std::string> earlier_outputs(const fs::path& manifest) {
  std::set<std::string> names;
  std::ifstream in(manifest);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.front() != '#') names.insert(line);
  return names;
}

/// What an earlier run left in a results directory.
struct EarlierRun {
  std::set<std::string> outputs;  ///< the names its manifest lists
  std::vector<fs::path> files;    ///< its manifest and outputs
  std::vector<fs::path> temporaries, folders;
};

/// Sorts the directory's contents into an earlier run's; throws InputError, touching nothing, when
/// it holds anything else (at the first such file: `--out /usr` walks no further) or cannot be read.
EarlierRun scan_earlier_run(const fs::path& dir, std::string_view option) {
  EarlierRun run;
  run.outputs = earlier_outputs(dir / kManifestName);
  std::vector<std::string> foreign;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && foreign.empty() && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string relative = it->path().lexically_relative(dir).generic_string();
    if (relative == kLockName) continue;  // the lock of the run that scans (held: lock_directory)
    std::error_code kind;
    if (it->is_directory(kind) && !it->is_symlink(kind)) {
      run.folders.push_back(it->path());
    } else if (is_leftover_temporary(it->path().filename().string())) {
      run.temporaries.push_back(it->path());
    } else if (relative == kManifestName || run.outputs.contains(relative)) {
      run.files.push_back(it->path());
    } else {
      foreign.push_back(relative);
    }
  }
  if (!foreign.empty())
    throw InputError(std::string(option) + " '" + dir.string() + "' holds files that no earlier jellysim run there "
                     "wrote (e.g. '" + foreign.front() +
                     "'); jellysim does not mix its results with other files: choose a new or empty directory");
  if (ec)
    throw InputError(std::string(option) + " '" + dir.string() + "' cannot be read through (" + ec.message() +
                     "): choose a new or empty directory");
  return run;
}

/// Refuses, before anything is read or written, an --out that cannot hold results: a path through a
/// file, or below a directory this process may not write into.
void check_out_location(const fs::path& dir) {
  std::error_code ec;
  fs::path at = fs::absolute(dir, ec).lexically_normal();
  while (!fs::exists(at, ec) && at.has_relative_path()) at = at.parent_path();
  if (!fs::is_directory(at, ec))
    throw InputError("--out '" + dir.string() + "': '" + at.string() + "' is a file, not a directory");
  if (::access(at.c_str(), W_OK | X_OK) != 0)
    throw InputError("--out '" + dir.string() + "': '" + at.string() + "' is not writable (" +
                     std::generic_category().message(errno) + "): choose a directory you can write to");
}

/// Removes an earlier run's outputs from `dir`, or throws InputError, touching nothing, when the
/// directory holds anything else.
void clear_earlier_run(const fs::path& dir) {
  const EarlierRun earlier = scan_earlier_run(dir, "--out");
  std::error_code ec;
  for (const fs::path& p : earlier.files) fs::remove(p, ec);
  for (const fs::path& p : earlier.temporaries) fs::remove(p, ec);
  std::vector<fs::path> folders = earlier.folders;
  // Deepest folders first, so a folder emptied of its subfolders goes too.
  std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
    return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
  });
  for (const fs::path& f : folders)
    if (fs::is_empty(f, ec)) fs::remove(f, ec);
}

}  // namespace

OutputDir OutputDir::for_run(std::filesystem::path dir, std::string_view command) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir, ec)) && !fs::is_directory(dir, ec))
    throw InputError("--out '" + dir.string() + "' is a file, not a directory");
  check_out_location(dir);  // before the lock creates it
  // A directory of other files is refused before a lock file is written into it (`--out /proc`);
  // the scan under the lock below is the one that counts.
  if (fs::is_directory(dir, ec)) scan_earlier_run(dir, "--out");
  std::shared_ptr<DirectoryLock> lock = lock_directory(dir, "--out");
  clear_earlier_run(dir);
  OutputDir out(std::move(dir));
  out.lock_ = std::move(lock);
  out.manifest_ = std::make_shared<RunManifest>(out.dir_ / kManifestName, command, new_run_id());
  return out;
}

OutputDir OutputDir::for_resumed_run(std::filesystem::path dir, std::string_view command) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / kManifestName, ec))
    throw InputError("--resume '" + dir.string() + "': not the results directory of a jellysim run (no " +
                     std::string(kManifestName) + ")");
  std::shared_ptr<DirectoryLock> lock = lock_directory(dir, "--resume");
  EarlierRun earlier = scan_earlier_run(dir, "--resume");
  for (const fs::path& p : earlier.temporaries) fs::remove(p, ec);
  std::string run_id = manifest_run_id(dir);
  OutputDir out(std::move(dir));
  out.lock_ = std::move(lock);
  out.manifest_ = std::make_shared<RunManifest>(out.dir_ / kManifestName, command,
                                                run_id.empty() ? new_run_id() : std::move(run_id),
                                                std::move(earlier.outputs));
  return out;
}

void OutputDir::remove(std::string_view name) const {
  std::error_code ec;
  fs::remove(dir_ / name, ec);
  if (ec) throw RunError("cannot remove '" + (dir_ / name).string() + "': " + ec.message());
  if (manifest_) manifest_->forget(prefix_ + std::string(name));
}

OutputDir OutputDir::subdirectory(std::string_view name) const {
  OutputDir sub(dir_ / name);
  sub.manifest_ = manifest_;
  sub.lock_ = lock_;
  sub.prefix_ = prefix_ + std::string(name) + "/";
  return sub;
}

void OutputDir::finish_manifest(bool keep_run_id) const {
  if (manifest_) manifest_->finish(keep_run_id);
}

std::string OutputDir::run_id() const { return manifest_ ? manifest_->run_id() : std::string(); }

OutputDir::OutputDir(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw RunError("cannot create output directory '" + dir_.string() + "': " + (ec ? ec.message() : "it is not a directory"));
  }
}

PendingFile OutputDir::temporary_for(std::string_view name) const {
  return PendingFile(*this, std::string(name), create_temporary_beside(dir_ / name));
}

PendingFile::PendingFile(PendingFile&& other) noexcept
    : dir_(std::move(other.dir_)), name_(std::move(other.name_)), file_(std::move(other.file_)) {
  other.file_ = {{}, -1};
}

PendingFile::~PendingFile() {
  if (file_.fd >= 0) ::close(file_.fd);
  if (!file_.path.empty()) ::unlink(file_.path.c_str());
}

void PendingFile::commit() {
  if (file_.fd < 0) throw std::logic_error("PendingFile::commit: already committed");
  const fs::path target = dir_.dir_ / name_;
  // Still our file under the temporary's name? (A thing planted there is neither followed nor
  // moved into place.)
  struct stat ours {}, named {};
  if (::fstat(file_.fd, &ours) != 0 || ::lstat(file_.path.c_str(), &named) != 0 || ours.st_dev != named.st_dev ||
      ours.st_ino != named.st_ino)
    throw RunError("cannot write '" + target.string() + "': its temporary '" + file_.path.string() +
                   "' was replaced while it was written");
  sync_and_close(file_.fd, target);  // on disk before it takes the final name
  // Listed before it takes its name: a run killed in between leaves nothing unlisted.
  if (dir_.manifest_) dir_.manifest_->record(dir_.prefix_ + name_);
  const fs::path temporary = std::exchange(file_.path, {});
  move_into_place(temporary, target);
}

void OutputDir::write_text(std::string_view name, std::string_view content) const {
  PendingFile file = temporary_for(name);
  write_all(file.fd(), content, dir_ / name);
  file.commit();
}

void OutputDir::write_json(std::string_view name, const nlohmann::ordered_json& json) const {
  write_text(name, json.dump(2) + "\n");
}

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

CsvWriter::CsvWriter(const std::vector<std::string>& columns) : columns_(columns.size()) {
  for (std::size_t i = 0; i < columns.size(); ++i) text_ += (i ? "," : "") + columns[i];
  text_ += '\n';
}

void CsvWriter::append_number(double v) { text_ += format_double(v); }

void CsvWriter::row(std::initializer_list<double> values) {
  if (values.size() != columns_) throw std::logic_error("CSV row has the wrong number of cells");
  bool first = true;
  for (double v : values) {
    if (!first) text_ += ',';
    append_number(v);
    first = false;
  }
  text_ += '\n';
  ++rows_;
}

void CsvWriter::row(std::initializer_list<std::string_view> labels, std::initializer_list<double> values) {
  if (labels.size() + values.size() != columns_) throw std::logic_error("CSV row has the wrong number of cells");
  bool first = true;
  for (std::string_view label : labels) {
    if (!first) text_ += ',';
    text_ += label;
    first = false;
  }
  for (double v : values) {
    text_ += ',';
    append_number(v);
  }
  text_ += '\n';
  ++rows_;
}

void CsvWriter::text_row(const std::vector<std::string>& cells) {
  if (cells.size() != columns_) throw std::logic_error("CSV row has the wrong number of cells");
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) text_ += ',';
    const std::string& cell = cells[i];
    if (cell.find_first_of(",\"\n\r") == std::string::npos) {
      text_ += cell;
      continue;
    }
    text_ += '"';
    for (char c : cell) text_ += c == '"' ? std::string("\"\"") : std::string(1, c);
    text_ += '"';
  }
  text_ += '\n';
  ++rows_;
}

}  // namespace jellysim::io
