#pragma once
// The memory budget a run must fit (issue 23): runs estimate what they will allocate before they
// allocate it and refuse, as an input error giving the estimate, what would not fit. Default: the
// smallest of half this machine's physical memory, what the process's own limits leave (RLIMIT_AS
// less what it has mapped, RLIMIT_DATA) and its cgroup's memory limit; `--memory-limit SIZE` sets it.
#include <cstdint>
#include <string>
#include <string_view>

namespace jellysim::core {

/// This machine's physical memory in bytes (0 when it cannot be told).
std::uint64_t physical_memory_bytes();
/// A budget and where it comes from ("--memory-limit", "half of this machine's memory", ...).
struct MemoryBudget {
  std::uint64_t bytes = 0;
  std::string source;
};
/// The default budget: the smallest of half the physical memory (else 4 GiB), what RLIMIT_AS leaves
/// beyond the address space mapped now, RLIMIT_DATA and the cgroup's memory.max (or v1's limit).
MemoryBudget default_memory_budget();
/// The budget: the one set, else the default.
MemoryBudget memory_budget();
std::uint64_t memory_budget_bytes();
/// Sets the budget (bytes, > 0); 0 restores the default.
void set_memory_budget_bytes(std::uint64_t bytes);
/// Names what this thread is doing while it lives (the innermost one counts), so that an allocation
/// that fails can be reported by the stage it failed in (issue 35, item 8): one that an exception
/// leaves records itself as the failed stage.
class MemoryStage {
 public:
  explicit MemoryStage(std::string what);
  ~MemoryStage();
  MemoryStage(const MemoryStage&) = delete;
  MemoryStage& operator=(const MemoryStage&) = delete;

 private:
  int exceptions_;
};
/// "out of memory (std::bad_alloc) while STAGE (the memory budget: 1.88 GiB, SOURCE)": the stage an
/// exception left last on this thread (then forgotten), or "while running" without one.
std::string out_of_memory_message();

/// "4G", "512M", "1.5GiB", "800k", "1000000" (bytes; k, M, G, T are powers of 1024, an optional
/// trailing "B" or "iB"); throws std::invalid_argument saying what is allowed.
std::uint64_t parse_byte_size(std::string_view text);
/// 1536 → "1.5 KiB", 3.2e9 → "2.98 GiB".
std::string format_bytes(double bytes);

}  // namespace jellysim::core
