#include "jellysim/core/memory.hpp"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace jellysim::core {

namespace {

std::atomic<std::uint64_t> g_budget{0};

}  // namespace

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

std::uint64_t memory_budget_bytes() {
  if (const std::uint64_t set = g_budget.load(); set > 0) return set;
  const std::uint64_t physical = physical_memory_bytes();
  return physical > 0 ? physical / 2 : std::uint64_t{4} << 30;
}

void set_memory_budget_bytes(std::uint64_t bytes) { g_budget.store(bytes); }

std::uint64_t parse_byte_size(std::string_view text) {
  const auto bad = [&] {
    return std::invalid_argument("memory size '" + std::string(text) +
                                 "' is not a size: a positive number of bytes with an optional unit k, M, G or T "
                                 "(powers of 1024), e.g. 4G or 512M");
  };
  std::size_t end = 0;
  double value = 0.0;
  try {
    value = std::stod(std::string(text), &end);
  } catch (const std::exception&) {
    throw bad();
  }
  std::string unit(text.substr(end));
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() >= 2 && unit.substr(unit.size() - 2) == "IB") unit.resize(unit.size() - 2);
  else if (!unit.empty() && unit.back() == 'B') unit.pop_back();
  double scale = 1.0;
  if (unit == "K") scale = 1024.0;
  else if (unit == "M") scale = 1024.0 * 1024.0;
  else if (unit == "G") scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!unit.empty()) throw bad();
  const double bytes = value * scale;
  if (!(bytes >= 1.0 && bytes < 1.8e19)) throw bad();
  return static_cast<std::uint64_t>(bytes);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
  char text[64];
  if (!std::isfinite(bytes)) return "more than can be counted";
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

}  // namespace jellysim::core
