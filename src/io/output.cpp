#include "jellysim/io/output.hpp"

#include "jellysim/core/errors.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <system_error>
#include <vector>
#include <fcntl.h>
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

}  // namespace

TemporaryFile create_temporary_beside(const fs::path& target) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path path = target;
    path += ".tmp-" + std::to_string(::getpid()) + temporary_suffix();
    // Exclusive: fails on anything already there, a symlink included (never followed).
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) return {std::move(path), fd};
    if (errno != EEXIST) throw RunError("cannot write '" + target.string() + "': " + os_reason(errno));
  }
  throw RunError("cannot write '" + target.string() + "': no free temporary name beside it");
}

void write_all(int fd, std::string_view content, const fs::path& shown) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RunError("cannot write '" + shown.string() + "': " + os_reason(errno));
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
}

void sync_file(const fs::path& path, const fs::path& shown) {
  Descriptor d{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW)};
  if (d.fd < 0) throw RunError("cannot write '" + shown.string() + "': " + os_reason(errno));
  if (::fsync(d.fd) != 0) throw RunError("cannot write '" + shown.string() + "': " + os_reason(errno));
}

void write_file_atomically(const fs::path& target, std::string_view content) {
  TemporaryFile tmp = create_temporary_beside(target);
  try {
    Descriptor d{tmp.fd};
    write_all(d.fd, content, target);
    if (::fsync(d.fd) != 0) throw RunError("cannot write '" + target.string() + "': " + os_reason(errno));
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp.path, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp.path, target, ec);
  if (ec) {
    fs::remove(tmp.path, ec);
    throw RunError("cannot write '" + target.string() + "': " + ec.message());
  }
}

/// The files a run wrote, kept on disk as the list grows, so a killed run still leaves it right.
class RunManifest {
 public:
  /// `names`: an earlier run's outputs that this run continues (a resumed run).
  RunManifest(fs::path file, std::string header, std::set<std::string> names = {})
      : file_(std::move(file)), header_(std::move(header)), names_(std::move(names)) {
    write_whole();
  }
  void record(const std::string& relative) {
    const std::lock_guard lock(mutex_);
    if (!names_.insert(relative).second) return;
    Descriptor d{::open(file_.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC)};
    if (d.fd < 0) throw RunError("cannot write '" + file_.string() + "': " + os_reason(errno));
    write_all(d.fd, relative + '\n', file_);
  }
  void finish() {
    const std::lock_guard lock(mutex_);
    write_whole();
  }
  void forget(const std::string& relative) {
    const std::lock_guard lock(mutex_);
    if (names_.erase(relative) > 0) write_whole();
  }

 private:
  void write_whole() const {
    std::string text = header_;
    for (const std::string& n : names_) text += n + '\n';
    write_file_atomically(file_, text);
  }

  std::mutex mutex_;
  fs::path file_;
  std::string header_;
  std::set<std::string> names_;
};

namespace {

/// A temporary of OutputDir (NAME.tmp-PID-RANDOM, or NAME.tmp-PID of earlier versions) that a
/// killed run left behind.
bool is_leftover_temporary(const std::string& name) {
  const std::size_t at = name.rfind(".tmp-");
  if (at == std::string::npos || at + 5 == name.size()) return false;
  const std::string_view tail = std::string_view(name).substr(at + 5);
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
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError("--out '" + dir.string() + "' is a file, not a directory");
  check_out_location(dir);
  if (fs::is_directory(dir, ec)) clear_earlier_run(dir);
  OutputDir out(std::move(dir));
  out.manifest_ = std::make_shared<RunManifest>(
      out.dir_ / kManifestName, "# jellysim " + std::string(command) +
                                    ": the files of this run; a later run into this directory removes them first\n");
  return out;
}

OutputDir OutputDir::for_resumed_run(std::filesystem::path dir, std::string_view command) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / kManifestName, ec))
    throw InputError("--resume '" + dir.string() + "': not the results directory of a jellysim run (no " +
                     std::string(kManifestName) + ")");
  EarlierRun earlier = scan_earlier_run(dir, "--resume");
  for (const fs::path& p : earlier.temporaries) fs::remove(p, ec);
  OutputDir out(std::move(dir));
  out.manifest_ = std::make_shared<RunManifest>(
      out.dir_ / kManifestName, "# jellysim " + std::string(command) +
                                    ": the files of this run; a later run into this directory removes them first\n",
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
  sub.prefix_ = prefix_ + std::string(name) + "/";
  return sub;
}

void OutputDir::finish_manifest() const {
  if (manifest_) manifest_->finish();
}

OutputDir::OutputDir(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw RunError("cannot create output directory '" + dir_.string() + "': " + ec.message());
  }
}

std::filesystem::path OutputDir::temporary_for(std::string_view name) const {
  TemporaryFile tmp = create_temporary_beside(dir_ / name);
  ::close(tmp.fd);  // the writer opens it by name (an empty regular file of ours)
  return tmp.path;
}

void OutputDir::commit(const std::filesystem::path& temporary, std::string_view name) const {
  const fs::path target = dir_ / name;
  std::error_code ec;
  try {
    sync_file(temporary, target);  // on disk before it takes the final name
  } catch (...) {
    std::filesystem::remove(temporary, ec);
    throw;
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw RunError("cannot write '" + target.string() + "': " + ec.message());
  }
  if (manifest_) manifest_->record(prefix_ + std::string(name));
}

void OutputDir::write_text(std::string_view name, std::string_view content) const {
  write_file_atomically(dir_ / name, content);
  if (manifest_) manifest_->record(prefix_ + std::string(name));
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
