#include "jellysim/core/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <vector>

namespace jellysim::core {

namespace {

std::atomic<std::uint64_t> g_budget{0};

}  // namespace

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

/// The soft limit of `resource` in bytes (kUnlimited when there is none).
std::uint64_t soft_limit(int resource) {
  rlimit r{};
  if (::getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return kUnlimited;
  return static_cast<std::uint64_t>(r.rlim_cur);
}

/// The address space this process has mapped already (its libraries, stacks, heap).
std::uint64_t address_space_in_use() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  const long page = ::sysconf(_SC_PAGESIZE);
  return statm >> pages && page > 0 ? pages * static_cast<std::uint64_t>(page) : 0;
}

/// A limit file's value: a number of bytes, or "max" (none).
std::uint64_t read_limit_file(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return kUnlimited;
  try {
    return std::stoull(text);
  } catch (const std::exception&) {
    return kUnlimited;
  }
}

/// The smallest memory limit of this process's cgroup and the cgroups above it, as mounted here:
/// cgroup v2's memory.max, or v1's memory.limit_in_bytes.
std::uint64_t cgroup_memory_limit() {
  std::ifstream in("/proc/self/cgroup");
  std::uint64_t smallest = kUnlimited;
  for (std::string line; std::getline(in, line);) {
    const std::size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const bool v2 = controllers.empty(), v1 = controllers.find("memory") != std::string::npos;
    if (!v2 && !v1) continue;
    const std::string mount = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    const char* file = v2 ? "/memory.max" : "/memory.limit_in_bytes";
    for (std::string path = line.substr(b + 1);; path.resize(path.rfind('/'))) {
      smallest = std::min(smallest, read_limit_file(mount + (path == "/" ? "" : path) + file));
      if (path.empty() || path == "/" || path.rfind('/') == std::string::npos) break;
    }
  }
  return smallest;
}

}  // namespace

MemoryBudget default_memory_budget() {
  const std::uint64_t physical = physical_memory_bytes();
  MemoryBudget b{physical > 0 ? physical / 2 : std::uint64_t{4} << 30,
                 physical > 0 ? "half of this machine's memory" : "4 GiB: this machine's memory is unknown"};
  const auto take = [&](std::uint64_t bytes, const char* source) {
    if (bytes < b.bytes) b = {bytes, source};
  };
  const std::uint64_t as = soft_limit(RLIMIT_AS), used = address_space_in_use();
  if (as != kUnlimited) take(as > used ? as - used : 1, "what this process's address-space limit (ulimit -v) leaves");
  take(soft_limit(RLIMIT_DATA), "this process's data-segment limit (ulimit -d)");
  take(cgroup_memory_limit(), "the memory limit of this process's cgroup (memory.max)");
  return b;
}

MemoryBudget memory_budget() {
  if (const std::uint64_t set = g_budget.load(); set > 0) return {set, "--memory-limit"};
  return default_memory_budget();
}

std::uint64_t memory_budget_bytes() { return memory_budget().bytes; }

namespace {
thread_local std::vector<std::string> t_stages;
thread_local std::string t_failed_stage;
}  // namespace

MemoryStage::MemoryStage(std::string what) : exceptions_(std::uncaught_exceptions()) {
  if (t_stages.empty()) t_failed_stage.clear();  // a stage an earlier, handled exception left
  t_stages.push_back(std::move(what));
}

MemoryStage::~MemoryStage() {
  if (std::uncaught_exceptions() > exceptions_ && t_failed_stage.empty()) t_failed_stage = t_stages.back();
  t_stages.pop_back();
}

std::string out_of_memory_message() {
  const std::string stage = t_failed_stage.empty() ? "running" : t_failed_stage;
  t_failed_stage.clear();
  const MemoryBudget b = memory_budget();
  return "out of memory (std::bad_alloc) while " + stage + " (the memory budget: " +
         format_bytes(static_cast<double>(b.bytes)) + ", " + b.source +
         "): free memory, coarsen tank.cells, raise jellyfish.spacing or record fewer frames";
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
