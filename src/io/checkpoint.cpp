#include "jellysim/io/checkpoint.hpp"

#include <cereal/archives/portable_binary.hpp>
#include <cereal/types/map.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/vector.hpp>
#include <zlib.h>

#include <fstream>
#include <sstream>

#include "jellysim/core/errors.hpp"

namespace jellysim::io {

namespace {

constexpr std::string_view kMagic = "jellysim checkpoint\n";
constexpr std::uint32_t kFormat = 1;

std::uint32_t crc32_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < bytes.size();) {  // zlib takes at most a uInt at a time
    const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size() - at, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), n);
    at += n;
  }
  return static_cast<std::uint32_t>(crc);
}

std::string little_endian(std::uint32_t v) {
  std::string s(4, '\0');
  for (int k = 0; k < 4; ++k) s[static_cast<std::size_t>(k)] = static_cast<char>((v >> (8 * k)) & 0xffu);
  return s;
}

std::uint32_t from_little_endian(std::string_view s) {
  std::uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(s[static_cast<std::size_t>(k)]);
  return v;
}

}  // namespace

void write_checkpoint(const OutputDir& out, const Checkpoint& c) {
  std::ostringstream body(std::ios::binary);
  {
    cereal::PortableBinaryOutputArchive ar(body);
    ar(kFormat, std::string(JELLYSIM_VERSION), c.command, c.scene_text, c.scene_source, c.sets, c.duration, c.every_s,
       c.state);
  }
  const std::string payload = body.str();
  out.write_text(kCheckpointName, std::string(kMagic) + payload + little_endian(crc32_of(payload)));
}

Checkpoint read_checkpoint(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / kCheckpointName;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError("--resume '" + dir.string() + "': no checkpoint there (" + std::string(kCheckpointName) +
                     "; write them with --checkpoint-every SECONDS)");
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw InputError("cannot read '" + file.string() + "'");
  const std::string damaged = "'" + file.string() + "' is not a whole jellysim checkpoint";
  if (bytes.size() < kMagic.size() + 4 || !bytes.starts_with(kMagic)) throw InputError(damaged);
  const std::string_view payload = std::string_view(bytes).substr(kMagic.size(), bytes.size() - kMagic.size() - 4);
  if (crc32_of(payload) != from_little_endian(std::string_view(bytes).substr(bytes.size() - 4)))
    throw InputError(damaged + " (its checksum does not match: the file was damaged)");
  Checkpoint c;
  std::uint32_t format = 0;
  std::string version;
  try {
    std::istringstream body{std::string(payload), std::ios::binary};
    cereal::PortableBinaryInputArchive ar(body);
    ar(format, version);
    if (format != kFormat || version != JELLYSIM_VERSION)
      throw InputError("'" + file.string() + "' was written by jellysim " + version +
                       " and this is jellysim " JELLYSIM_VERSION ": a checkpoint resumes with the version that wrote it");
    ar(c.command, c.scene_text, c.scene_source, c.sets, c.duration, c.every_s, c.state);
  } catch (const cereal::Exception& e) {
    throw InputError(damaged + " (" + e.what() + ")");
  }
  return c;
}

}  // namespace jellysim::io
