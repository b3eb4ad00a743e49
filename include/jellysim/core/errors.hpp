#pragma once
// Error categories that map to the CLI's exit codes (docs/cli.md).
#include <stdexcept>

namespace jellysim {

/// Bad user input (scene file, --set value, CLI option, input file). Exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A run that started but failed (diverged simulation, unwritable output). Exit code 1.
struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace jellysim
