#pragma once
// docs/parameters.md: every scene parameter table as Markdown, generated so that it cannot go stale
// (`jellysim scenes --reference > docs/parameters.md`; a test compares the file with this text).
#include <string>

namespace jellysim::scene {

std::string parameters_reference();

}  // namespace jellysim::scene
