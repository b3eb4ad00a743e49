#pragma once
// A simulation's history as named arrays of bytes: what a checkpoint holds (issue 23). A stateful
// class lists its members once, in `void archive(core::StateArchive&)`, which saves them into the
// archive or restores them from it, so that the two directions cannot disagree. Values are kept
// as they are in memory (a double's bits), so a restored simulation continues bit for bit.
// Knows nothing of files: io/checkpoint writes an archive's entries and reads them back.
#include <cstddef>
#include <cstring>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace jellysim::core {

/// A checkpoint that does not fit the simulation it is restored into (another scene or build).
class StateMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  using Entries = std::map<std::string, std::string, std::less<>>;  ///< name → bytes

  /// An empty archive that the archive() functions fill.
  static StateArchive saving() { return StateArchive(false, {}); }
  /// An archive the archive() functions restore from; entries as saved.
  static StateArchive restoring(Entries entries) { return StateArchive(true, std::move(entries)); }

  bool is_restoring() const { return restoring_; }
  const Entries& entries() const { return entries_; }
  /// The saved entries, moved out (the archive is empty after).
  Entries take_entries() { return std::move(entries_); }

  /// Names made inside a scope get its prefix ("world.fluid.velocity.u").
  class Scope {
   public:
    Scope(StateArchive& archive, std::string_view name) : archive_(archive), length_(archive.prefix_.size()) {
      archive_.prefix_.append(name).push_back('.');
    }
    ~Scope() { archive_.prefix_.resize(length_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StateArchive& archive_;
    std::size_t length_;
  };

  /// One value of a trivially copyable type (a number, a flag, a small vector type).
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void value(std::string_view name, T& v) {
    values(name, std::span<T>(&v, 1));
  }
  /// An array whose length the restoring simulation already has (a field on its grid): a saved
  /// array of another length is a StateMismatch.
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void values(std::string_view name, std::span<T> v) {
    if (!restoring_) {
      put(name, v.data(), v.size_bytes());
      return;
    }
    const std::string& bytes = get(name);
    if (bytes.size() != v.size_bytes())
      throw StateMismatch("checkpoint entry '" + prefix_ + std::string(name) + "' has " +
                          std::to_string(bytes.size() / sizeof(T)) + " values where this simulation has " +
                          std::to_string(v.size()));
    if (!bytes.empty()) std::memcpy(static_cast<void*>(v.data()), bytes.data(), bytes.size());
  }
  /// An array whose length is part of the state (resized when restoring).
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void vector(std::string_view name, std::vector<T>& v) {
    if (restoring_) {
      const std::string& bytes = get(name);
      if (bytes.size() % sizeof(T) != 0)
        throw StateMismatch("checkpoint entry '" + prefix_ + std::string(name) + "' is not an array of this type");
      v.resize(bytes.size() / sizeof(T));
    }
    values(name, std::span<T>(v));
  }
  /// Arrays of arrays (e.g. per frame, per body): their lengths, then their values end to end.
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void nested(std::string_view name, std::vector<std::vector<T>>& v) {
    const Scope scope(*this, name);
    std::vector<std::size_t> lengths;
    std::vector<T> flat;
    if (!restoring_)
      for (const std::vector<T>& inner : v) lengths.push_back(inner.size()), flat.insert(flat.end(), inner.begin(), inner.end());
    vector("lengths", lengths);
    vector("values", flat);
    if (!restoring_) return;
    std::size_t total = 0;
    for (std::size_t n : lengths) total += n;
    if (total != flat.size()) throw StateMismatch("checkpoint entry '" + prefix_ + "' has inconsistent lengths");
    v.assign(lengths.size(), {});
    std::size_t offset = 0;
    for (std::size_t k = 0; k < lengths.size(); offset += lengths[k], ++k)
      v[k].assign(flat.begin() + static_cast<std::ptrdiff_t>(offset),
                  flat.begin() + static_cast<std::ptrdiff_t>(offset + lengths[k]));
  }
  void text(std::string_view name, std::string& s);
  /// The length of a sequence whose elements archive themselves one by one (e.g. recorded frames):
  /// saved, or restored into `v` (resized; a length beyond the entries' count is damage).
  template <class T>
  void length(std::string_view name, std::vector<T>& v) {
    std::size_t count = v.size();
    value(name, count);
    if (!restoring_) return;
    if (count > entries_.size())
      throw StateMismatch("checkpoint entry '" + prefix_ + std::string(name) + "' is damaged");
    v.assign(count, T{});
  }

  /// Restoring: throws StateMismatch naming an entry that no archive() function read (a
  /// checkpoint of a different simulation).
  void check_all_read() const;

 private:
  StateArchive(bool restoring, Entries entries) : restoring_(restoring), entries_(std::move(entries)) {}
  void put(std::string_view name, const void* data, std::size_t bytes);
  const std::string& get(std::string_view name);

  bool restoring_;
  Entries entries_;
  std::string prefix_;
  std::set<std::string, std::less<>> read_;
};

}  // namespace jellysim::core
