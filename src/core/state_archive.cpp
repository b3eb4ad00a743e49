#include "jellysim/core/state_archive.hpp"

namespace jellysim::core {

void StateArchive::put(std::string_view name, const void* data, std::size_t bytes) {
  std::string key = prefix_ + std::string(name);
  if (entries_.contains(key)) throw std::logic_error("state archive: '" + key + "' saved twice");
  entries_.emplace(std::move(key), std::string(static_cast<const char*>(data), bytes));
}

const std::string& StateArchive::get(std::string_view name) {
  const std::string key = prefix_ + std::string(name);
  const auto it = entries_.find(key);
  if (it == entries_.end()) throw StateMismatch("the checkpoint has no entry '" + key + "' (another scene or version)");
  read_.insert(key);
  return it->second;
}

void StateArchive::text(std::string_view name, std::string& s) {
  if (!restoring_) {
    put(name, s.data(), s.size());
    return;
  }
  s = get(name);
}

void StateArchive::check_all_read() const {
  for (const auto& [key, bytes] : entries_)
    if (!read_.contains(key))
      throw StateMismatch("the checkpoint has an entry '" + key + "' this simulation does not (another scene or version)");
}

}  // namespace jellysim::core
