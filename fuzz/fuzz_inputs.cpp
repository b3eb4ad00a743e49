// libFuzzer target over what a user hands jellysim (issue 23): scene files (parsed, merged onto the
// built-in jellyfish scene, read and validated — as `jellysim simulate SCENE` does before running),
// polygon outline files and IB2d structure files. Every input must either be accepted or refused
// with an InputError (exit 2 in the CLI); any other exception, a crash, a sanitizer report, a leak
// or a hang is a bug. The first byte picks the reader: 'p' a polygon file, 'v' an IB2d structure
// (STEM.vertex, then after a line "---" STEM.spring), anything else a scene (from the second byte
// when the first is 's'). Seeds: the shipped scenes and files (fuzz/CMakeLists.txt).
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//config/config.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/io/ib2d_files.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace {

namespace fs = std::filesystem;
using namespace jellysim;

/// A scratch directory of this process for the file readers.
const fs::path& scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("jellysim-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

void write(const fs::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

/// The built-in jellyfish scene with `overlay` merged onto it, read and validated (a 3D scene by
/// the 3D reader, as `jellysim simulate` does).
void read_scene(std::string_view overlay) {
  config::Config c = scene::builtin_jellyfish_scene();
  c.merge(config::Config::parse(overlay, "fuzz.toml"));
  if (scene::is_3d_scene(c)) scene::read_swim3d_settings(c);
  else scene::read_swim_settings(c);
}

void read_polygon(std::string_view text) {
  const fs::path file = scratch() / "outline.txt";
  write(file, text);
  read_scene("[[objects]]\ntype = \"polygon\"\nfile = \"" + file.string() + "\"\n");
}

void read_ib2d(std::string_view text) {
  const std::size_t split = text.find("\n---\n");
  write(scratch() / "s.vertex", text.substr(0, split));
  std::error_code ignored;
  fs::remove(scratch() / "s.spring", ignored);
  if (split != std::string_view::npos) write(scratch() / "s.spring", text.substr(split + 5));
  io::read_ib2d_structure(scratch() / "s");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const char kind = input.empty() ? 's' : input.front();
  const std::string_view rest = input.empty() ? input : input.substr(1);
  try {
    if (kind == 'p') read_polygon(rest);
    else if (kind == 'v') read_ib2d(rest);
    else read_scene(kind == 's' ? rest : input);
  } catch (const InputError&) {
    // Refused with a message: what bad input must get.
  }
  return 0;
}
