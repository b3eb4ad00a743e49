#pragma once
// Shared by the scene tests: a source file's text (generated files are compared with it) and the
// message of the InputError a call throws.
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::testing {

inline std::string read_source_file(const std::string& relative) {
  std::ifstream in(std::string(JELLYSIM_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The InputError's message, or "" when f throws none.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace jellysim::testing
