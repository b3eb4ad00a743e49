#pragma once
// The memory budget a run must fit (issue 23): runs estimate what they will allocate before they
// allocate it and refuse, as an input error giving the estimate, what would not fit. Default: half
// of this machine's physical memory; `--memory-limit SIZE` sets it.
#include <cstdint>
#include <string>
#include <string_view>

namespace jellysim::core {

/// This machine's physical memory in bytes (0 when it cannot be told).
std::uint64_t physical_memory_bytes();
/// The budget: the one set, else half the physical memory (else 4 GiB).
std::uint64_t memory_budget_bytes();
/// Sets the budget (bytes, > 0); 0 restores the default.
void set_memory_budget_bytes(std::uint64_t bytes);
/// "4G", "512M", "1.5GiB", "800k", "1000000" (bytes; k, M, G, T are powers of 1024, an optional
/// trailing "B" or "iB"); throws std::invalid_argument saying what is allowed.
std::uint64_t parse_byte_size(std::string_view text);
/// 1536 → "1.5 KiB", 3.2e9 → "2.98 GiB".
std::string format_bytes(double bytes);

}  // namespace jellysim::core
