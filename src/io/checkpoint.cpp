#include "jellysim/io/checkpoint.hpp"

#include <cereal/archives/portable_binary.hpp>
#include <cereal/types/map.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/vector.hpp>
#include <zlib.h>

#include <cerrno>
#include <new>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "jellysim/core/errors.hpp"

namespace jellysim::io {

namespace {

namespace fs = std::filesystem;

// Format 2: MAGIC, header length (8 bytes), header, its CRC-32, state, its CRC-32 (little endian).
constexpr std::string_view kMagic = "jellysim checkpoint 2\n";
constexpr std::string_view kFormat1Magic = "jellysim checkpoint\n";  // format 1 (one CRC, no run id)
constexpr std::uint32_t kFormat = 2;
/// A header holds a scene file's text (at most 1 MiB: Config::kMaxSceneFileBytes) and small fields.
constexpr std::uint64_t kMaxHeaderBytes = std::uint64_t{4} << 20;

std::uint32_t crc32_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < bytes.size();) {  // zlib takes at most a uInt at a time
    const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size() - at, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), n);
    at += n;
  }
  return static_cast<std::uint32_t>(crc);
}

std::string little_endian(std::uint64_t v, int bytes) {
  std::string s(static_cast<std::size_t>(bytes), '\0');
  for (int k = 0; k < bytes; ++k) s[static_cast<std::size_t>(k)] = static_cast<char>((v >> (8 * k)) & 0xffu);
  return s;
}

std::uint64_t from_little_endian(std::string_view s) {
  std::uint64_t v = 0;
  for (std::size_t k = s.size(); k-- > 0;) v = (v << 8) | static_cast<unsigned char>(s[k]);
  return v;
}

/// The checkpoint file, opened once: a regular file (never a link, a pipe or a device), read by offset.
class CheckpointFile {
 public:
  explicit CheckpointFile(const fs::path& file) : file_(file) {
    fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW);
    if (fd_ < 0) throw InputError("cannot read '" + file.string() + "': " + os_reason(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd_);
      throw InputError("'" + file.string() + "' is not a regular file");
    }
    size_ = static_cast<std::uint64_t>(st.st_size);
  }
  ~CheckpointFile() { ::close(fd_); }
  CheckpointFile(const CheckpointFile&) = delete;
  CheckpointFile& operator=(const CheckpointFile&) = delete;

  std::uint64_t size() const { return size_; }
  /// `bytes` bytes at `offset` (the caller has checked they are inside the file).
  std::string read(std::uint64_t offset, std::uint64_t bytes) const {
    std::string out(static_cast<std::size_t>(bytes), '\0');
    for (std::size_t at = 0; at < out.size();) {
      const ssize_t n = ::pread(fd_, out.data() + at, out.size() - at, static_cast<off_t>(offset + at));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw InputError("cannot read '" + file_.string() + "': " + (n < 0 ? os_reason(errno) : "it shrank"));
      at += static_cast<std::size_t>(n);
    }
    return out;
  }

 private:
  fs::path file_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// `bytes` followed by its CRC-32 at `offset`; InputError `damaged` when the CRC does not match.
std::string read_checked(const CheckpointFile& f, std::uint64_t offset, std::uint64_t bytes, const std::string& damaged) {
  const std::string block = f.read(offset, bytes + 4);
  const std::string_view body = std::string_view(block).substr(0, static_cast<std::size_t>(bytes));
  if (crc32_of(body) != from_little_endian(std::string_view(block).substr(static_cast<std::size_t>(bytes))))
    throw InputError(damaged + " (its checksum does not match: the file was damaged)");
  return std::string(body);
}

/// Parses a block with cereal; InputError `damaged` when it does not parse.
template <class Read>
void parse(const std::string& block, const std::string& damaged, Read&& read) {
  try {
    std::istringstream body{block, std::ios::binary};
    cereal::PortableBinaryInputArchive ar(body);
    read(ar);
  } catch (const cereal::Exception& e) {
    throw InputError(damaged + " (" + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw InputError(damaged + " (a length in it is out of range)");
  } catch (const std::length_error&) {
    throw InputError(damaged + " (a length in it is out of range)");
  }
}

void check_run_id(const Checkpoint& c, const fs::path& dir) {
  const std::string folder = manifest_run_id(dir);
  if (c.run_id == folder) return;
  throw InputError("'" + c.file.string() + "' is the checkpoint of another run than the one in '" +
                   (dir / kManifestName).string() + "' (run " + c.run_id + "; the directory's: " +
                   (folder.empty() ? "none" : "run " + folder) +
                   "): a checkpoint resumes only the run that wrote it, in its own directory");
}

}  // namespace

void write_checkpoint(const OutputDir& out, const Checkpoint& c) {
  std::ostringstream header(std::ios::binary), state(std::ios::binary);
  {
    cereal::PortableBinaryOutputArchive ar(header);
    ar(kFormat, std::string(JELLYSIM_VERSION), out.run_id(), c.command, c.scene_text, c.scene_source, c.sets,
       c.duration, c.every_s, c.inputs);
  }
  {
    cereal::PortableBinaryOutputArchive ar(state);
    ar(c.state);
  }
  const std::string h = header.str(), s = state.str();
  out.write_text(kCheckpointName, std::string(kMagic) + little_endian(h.size(), 8) + h +
                                      little_endian(crc32_of(h), 4) + s + little_endian(crc32_of(s), 4));
}

Checkpoint read_checkpoint(const fs::path& dir) {
  Checkpoint c;
  c.file = dir / kCheckpointName;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(c.file, ec)))
    throw InputError("--resume '" + dir.string() + "': no checkpoint there (" + std::string(kCheckpointName) +
                     "; write them with --checkpoint-every SECONDS)");
  const CheckpointFile f(c.file);
  const std::string damaged = "'" + c.file.string() + "' is not a whole jellysim checkpoint";
  const std::uint64_t lead = kMagic.size() + 8;
  if (f.size() >= kFormat1Magic.size() && f.read(0, kFormat1Magic.size()) == kFormat1Magic)
    throw InputError("'" + c.file.string() + "' was written by an earlier jellysim (checkpoint format 1) and this is "
                     "jellysim " JELLYSIM_VERSION ": a checkpoint resumes with the version that wrote it");
  if (f.size() < lead + 8 || f.read(0, kMagic.size()) != kMagic) throw InputError(damaged);
  const std::uint64_t header_bytes = from_little_endian(f.read(kMagic.size(), 8));
  if (header_bytes > kMaxHeaderBytes || header_bytes + 8 > f.size() - lead) throw InputError(damaged);
  std::uint32_t format = 0;
  std::string version;
  parse(read_checked(f, lead, header_bytes, damaged), damaged, [&](auto& ar) {
    ar(format, version);
    if (format != kFormat || version != JELLYSIM_VERSION)
      throw InputError("'" + c.file.string() + "' was written by jellysim " + version +
                       " and this is jellysim " JELLYSIM_VERSION ": a checkpoint resumes with the version that wrote it");
    ar(c.run_id, c.command, c.scene_text, c.scene_source, c.sets, c.duration, c.every_s, c.inputs);
  });
  c.state_offset = lead + header_bytes + 4;
  c.state_bytes = f.size() - c.state_offset - 4;
  check_run_id(c, dir);
  return c;
}

core::StateArchive::Entries read_checkpoint_state(const Checkpoint& c, double most_bytes) {
  if (static_cast<double>(c.state_bytes) > most_bytes)
    throw InputError("'" + c.file.string() + "' holds " + std::to_string(c.state_bytes) +
                     " bytes of state, more than this run's configuration can have (at most " +
                     std::to_string(static_cast<std::uint64_t>(most_bytes)) +
                     "): it is not this run's checkpoint, or it was damaged");
  const CheckpointFile f(c.file);
  const std::string damaged = "'" + c.file.string() + "' is not a whole jellysim checkpoint";
  if (f.size() != c.state_offset + c.state_bytes + 4) throw InputError(damaged + " (it changed while it was read)");
  core::StateArchive::Entries state;
  parse(read_checked(f, c.state_offset, c.state_bytes, damaged), damaged, [&](auto& ar) { ar(state); });
  return state;
}

}  // namespace jellysim::io
