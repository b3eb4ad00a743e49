#pragma once
// Checkpoint files (issue 23): a run's whole state (core::StateArchive entries) and how the run was
// configured, so that `jellysim simulate --resume DIR` continues a killed run bit for bit. One file
// in the results directory, replaced atomically (temporary, fsync, rename) at each checkpoint, in
// cereal's portable binary format with a CRC-32 of its contents; a checkpoint of another version
// of jellysim is refused (the state's layout is the build's).
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::io {

inline constexpr std::string_view kCheckpointName = "checkpoint.jellysim";

struct Checkpoint {
  std::string command;       ///< the command that wrote it ("simulate")
  std::string scene_text;    ///< the scene file's text ("" for the built-in scene)
  std::string scene_source;  ///< the scene file's name, for messages
  std::vector<std::string> sets;  ///< the --set overrides, in order
  std::string duration;      ///< --duration as given ("" when it was not)
  double every_s = 0.0;      ///< --checkpoint-every, simulated seconds
  core::StateArchive::Entries state;
};

/// Writes out/checkpoint.jellysim atomically; errors name the file and the OS reason.
void write_checkpoint(const OutputDir& out, const Checkpoint& checkpoint);
/// Reads DIR/checkpoint.jellysim; InputError when it is missing, damaged (the CRC), or written by
/// another version of jellysim.
Checkpoint read_checkpoint(const std::filesystem::path& dir);

}  // namespace jellysim::io
