#pragma once
// Results directory: every file is written atomically (temporary name, then rename), so a reader
// never sees a half-written file and a failed run leaves no corrupt output behind.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace jellysim::io {

class RunManifest;
class PendingFile;

/// A new file made exclusively beside `target` (TARGET.tmp-PID-RANDOM, O_CREAT|O_EXCL|O_NOFOLLOW:
/// never an existing file or a planted symlink) and its open descriptor, for writing.
struct TemporaryFile {
  std::filesystem::path path;
  int fd;
};
TemporaryFile create_temporary_beside(const std::filesystem::path& target);
/// Writes all of `content` to `fd`; a failure throws RunError naming `shown` and the OS reason.
void write_all(int fd, std::string_view content, const std::filesystem::path& shown);
/// Writes `target` through an exclusive temporary beside it, fsync, then rename: a reader sees
/// the old file or the whole new one; errors name the target and the OS reason.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);
/// Writes `content` to `path`, created or truncated in place, never through a symlink there
/// (O_NOFOLLOW): the path writers of single files (a results directory writes atomically instead);
/// errors name the path and the reason of the call that failed.
void write_file(const std::filesystem::path& path, std::string_view content);
/// The operating system's text for an errno value (thread-safe).
std::string os_reason(int error_number);
/// The whole content of `path`, which must be a regular file of at most `max_bytes` (checked with
/// fstat on the opened file, before reading: never a named pipe, a device or a directory, which
/// are not waited on); with `follow_links` false a symbolic link is refused too (O_NOFOLLOW).
/// Throws InputError naming the file and what it is.
std::string read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, bool follow_links);

/// The advisory lock of a results directory (flock on DIR/.jellysim.lock) that a run holds for its
/// life, so that two runs never write into one directory at once; removed when released.
class DirectoryLock;
/// Creates `dir` if needed and locks it; a directory another process holds is an InputError naming
/// `option`, the directory and the holder's pid (as its lock file says).
std::shared_ptr<DirectoryLock> lock_directory(const std::filesystem::path& dir, std::string_view option);
/// The lock file's name in a results directory (not a result: never in a manifest).
inline constexpr std::string_view kLockName = ".jellysim.lock";

class OutputDir {
 public:
  /// Creates the directory (and parents) if needed; throws RunError when that fails.
  explicit OutputDir(std::filesystem::path dir);

  /// The results directory of a command (`--out`): it must be new, empty, or hold only an earlier
  /// run's outputs (listed in its manifest.txt, plus temporaries a killed run left). Those are
  /// removed first, so the directory never mixes two runs; anything else makes it an InputError
  /// (exit 2) and nothing is touched. Every file this run writes, here or in subdirectory()s, is
  /// listed in manifest.txt as it is written (sorted when the run ends: finish_manifest()).
  /// The directory is locked (lock_directory) for as long as a copy of the result lives: a
  /// directory another run is writing is an InputError naming it and that run's pid.
  static OutputDir for_run(std::filesystem::path dir, std::string_view command);
  /// The results directory of a run that continues there (`simulate --resume`): the earlier run's
  /// outputs stay and remain in the manifest, temporaries it left are removed; a directory
  /// without a manifest, or holding other files, is an InputError. Locked as for_run's.
  static OutputDir for_resumed_run(std::filesystem::path dir, std::string_view command);
  /// The directory `name` inside this one, created if needed; its files join this run's manifest.
  OutputDir subdirectory(std::string_view name) const;
  /// Rewrites manifest.txt in sorted order (the order files were written in may vary with threads).
  /// The run's id (run_id()) stays in it only with `keep_run_id` (a run that can still be resumed),
  /// so that a whole run's manifest is the same bytes every time.
  void finish_manifest(bool keep_run_id = false) const;
  /// The run's identity: random, in the manifest's first line while the run goes on, kept by a
  /// resumed run; a checkpoint carries it, so that it resumes only the run (and directory) it is of.
  /// Empty for a plain directory.
  std::string run_id() const;

  const std::filesystem::path& path() const { return dir_; }
  std::filesystem::path file(std::string_view name) const { return dir_ / name; }

  /// Writes `content` to `name` atomically.
  void write_text(std::string_view name, std::string_view content) const;
  /// Writes a JSON document (2-space indented, trailing newline) atomically.
  void write_json(std::string_view name, const nlohmann::ordered_json& json) const;
  /// Removes the file `name` (one of this run's) and its line in the manifest.
  void remove(std::string_view name) const;

  /// For writers that fill a file through a descriptor (ffmpeg): a new file made exclusively next
  /// to `name` (create_temporary_beside), open for writing. Write through its descriptor, never
  /// reopen it by name; PendingFile::commit() moves it into place. One that is not committed is
  /// removed; one a killed run left keeps its ".tmp-" name, which no reader takes for a result,
  /// and the next run into the directory removes it.
  PendingFile temporary_for(std::string_view name) const;

 private:
  friend class PendingFile;
  std::filesystem::path dir_;
  std::shared_ptr<RunManifest> manifest_;  ///< null for a plain directory
  std::shared_ptr<DirectoryLock> lock_;    ///< held while any copy lives (null for a plain directory)
  std::string prefix_;                     ///< this directory relative to the manifest's ("" or "frames/")
};

/// The manifest's file name in a run's results directory.
inline constexpr std::string_view kManifestName = "manifest.txt";
/// The run id in DIR/manifest.txt's first line ("" when there is none: a whole run's, or no manifest).
std::string manifest_run_id(const std::filesystem::path& dir);

/// A file of an OutputDir being written through its descriptor (OutputDir::temporary_for).
class PendingFile {
 public:
  PendingFile(PendingFile&& other) noexcept;
  PendingFile& operator=(PendingFile&&) = delete;
  ~PendingFile();  ///< an uncommitted file is closed and removed

  int fd() const { return file_.fd; }
  const std::filesystem::path& path() const { return file_.path; }
  /// Syncs the file through its descriptor, closes it, lists it in the run's manifest and renames
  /// it into place. Throws RunError (the file removed) when a call fails, or when something else
  /// took the temporary's name meanwhile (nothing is moved into place then).
  void commit();

 private:
  friend class OutputDir;
  PendingFile(OutputDir dir, std::string name, TemporaryFile file)
      : dir_(std::move(dir)), name_(std::move(name)), file_(std::move(file)) {}
  OutputDir dir_;
  std::string name_;
  TemporaryFile file_;
};

/// Writes `name` of `out` atomically from a writer that streams it (`writer(std::ostream&)`, e.g.
/// the VTK writers); nothing is written when the writer throws.
template <class Writer>
void write_streamed(const OutputDir& out, std::string_view name, Writer&& writer) {
  std::ostringstream bytes;
  writer(static_cast<std::ostream&>(bytes));
  out.write_text(name, bytes.view());
}

/// Builds a CSV file row by row with a fixed header; numbers use the shortest text that reads back
/// to the same double (std::to_chars), so files are byte-identical across runs.
class CsvWriter {
 public:
  explicit CsvWriter(const std::vector<std::string>& columns);
  /// Appends one row of numbers; the count must equal the column count.
  void row(std::initializer_list<double> values);
  /// Appends one row whose first cell is text (e.g. an integrator name) followed by numbers.
  void row(std::string_view label, std::initializer_list<double> values) { row({label}, values); }
  /// Appends one row whose first cells are text, followed by numbers.
  void row(std::initializer_list<std::string_view> labels, std::initializer_list<double> values);
  /// Appends one row of cells already written as text (numbers through format_double); a cell
  /// holding a comma, a quote or a line break is quoted, its quotes doubled (RFC 4180).
  void text_row(const std::vector<std::string>& cells);
  const std::string& text() const { return text_; }
  std::size_t rows() const { return rows_; }

 private:
  void append_number(double v);
  std::size_t columns_;
  std::size_t rows_ = 0;
  std::string text_;
};

/// Shortest round-trip text for a double ("nan"/"inf" for non-finite values).
std::string format_double(double v);

}  // namespace jellysim::io
