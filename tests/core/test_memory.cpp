// The memory budget's sizes (issue 23, core/memory.hpp).
#include <gtest/gtest.h>

#include <stdexcept>

#include "jellysim/core/memory.hpp"

namespace jellysim::core {
namespace {

TEST(MemoryBudget, ParsesSizesWithBinaryUnits) {
  EXPECT_EQ(parse_byte_size("1000000"), 1000000u);
  EXPECT_EQ(parse_byte_size("800k"), 800u * 1024u);
  EXPECT_EQ(parse_byte_size("512M"), 512ull << 20);
  EXPECT_EQ(parse_byte_size("4G"), 4ull << 30);
  EXPECT_EQ(parse_byte_size("1.5GiB"), 3ull << 29);
  EXPECT_EQ(parse_byte_size("2TB"), 2ull << 40);
  for (const char* bad : {"", "G", "-1G", "0", "12Q", "nan", "inf", "1e30", "4 G"})
    EXPECT_THROW(parse_byte_size(bad), std::invalid_argument) << bad;
}

TEST(MemoryBudget, DefaultsToHalfThePhysicalMemoryAndCanBeSet) {
  set_memory_budget_bytes(0);
  const std::uint64_t physical = physical_memory_bytes();
  ASSERT_GT(physical, 0u);
  // Half the physical memory, or less where the process's own limits (ulimit, cgroup) leave less.
  const MemoryBudget fallback = default_memory_budget();
  EXPECT_LE(fallback.bytes, physical / 2);
  EXPECT_GT(fallback.bytes, 0u);
  EXPECT_EQ(fallback.bytes == physical / 2, fallback.source == "half of this machine's memory") << fallback.source;
  EXPECT_EQ(memory_budget_bytes(), fallback.bytes);
  set_memory_budget_bytes(123456789);
  EXPECT_EQ(memory_budget_bytes(), 123456789u);
  EXPECT_EQ(memory_budget().source, "--memory-limit");
  set_memory_budget_bytes(0);
  EXPECT_EQ(memory_budget_bytes(), fallback.bytes);
}

TEST(MemoryBudget, FormatsBytes) {
  EXPECT_EQ(format_bytes(512), "512 B");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(format_bytes(100.0 * 1024 * 1024), "100 MiB");
  EXPECT_EQ(format_bytes(3.2e9), "2.98 GiB");
}

}  // namespace
}  // namespace jellysim::core
