#pragma once
// Checkpoint files (issue 23): a run's whole state (core::StateArchive entries) and how the run was
// configured, so that `jellysim simulate --resume DIR` continues a killed run bit for bit. One file
// in the results directory, replaced atomically (temporary, fsync, rename) at each checkpoint, in
// cereal's portable binary format: a header (the format, the version of jellysim, the run's id, its
// configuration as given and the files its scene read) with its own CRC-32, then the state with
// its CRC-32. A checkpoint of another version of jellysim is refused (the state's layout is the
// build's), and so is one of another run (its run id is not the directory's: io::manifest_run_id).
// The header is read and checked first; the state only once its size is known to fit what the
// run's configuration implies (read_checkpoint_state), so that a huge file is refused at once.
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
  std::string run_id;        ///< the run's (OutputDir::run_id): it resumes only in that run's directory
  std::string command;       ///< the command that wrote it ("simulate")
  std::string scene_text;    ///< the scene file's text ("" for the built-in scene)
  std::string scene_source;  ///< the scene file's name, for messages
  std::vector<std::string> sets;  ///< the --set overrides, in order
  std::string duration;      ///< --duration as given ("" when it was not)
  double every_s = 0.0;      ///< --checkpoint-every, simulated seconds
  std::vector<std::string> inputs;  ///< files the scene read besides itself (IB2d structure files)
  core::StateArchive::Entries state;  ///< written; read by read_checkpoint_state
  /// Where read_checkpoint found the state (unused when writing).
  std::filesystem::path file;
  std::uint64_t state_offset = 0, state_bytes = 0;
};

/// Writes out/checkpoint.jellysim atomically, with out's run id; errors name the file and the OS reason.
void write_checkpoint(const OutputDir& out, const Checkpoint& checkpoint);
/// Reads DIR/checkpoint.jellysim's header (not its state); InputError when it is missing, not a
/// regular file, damaged (the CRC), written by another version of jellysim, or of another run than
/// DIR/manifest.txt's (naming both files).
Checkpoint read_checkpoint(const std::filesystem::path& dir);
/// Reads the state of a checkpoint read_checkpoint returned; InputError, before reading it, when
/// it is larger than `most_bytes` (what the run's configuration can hold), and when it is damaged.
core::StateArchive::Entries read_checkpoint_state(const Checkpoint& checkpoint, double most_bytes);

}  // namespace jellysim::io
