// The sanitized programs' default options (src/app/sanitizer_defaults.cpp) keep LeakSanitizer
// working when a dynamic TLS block lands 16 bytes past a page boundary. With GCC 12's runtime and
// its __tls_get_addr interceptor on, the leak check below dies in the tracer ("Tracer caught
// signal 11"), as `jellysim run` did on the CI machine with one of Mesa's blocks.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <dlfcn.h>
#include <future>
#include <memory>
#include <thread>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define JELLYSIM_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JELLYSIM_TEST_ASAN 1
#endif
#endif
#if defined(JELLYSIM_TEST_ASAN)
#include <sanitizer/lsan_interface.h>
#endif

namespace {

#if defined(JELLYSIM_TEST_ASAN)
constexpr std::size_t kProbeTlsBytes = 24;  // sizeof tls_probe_buffer: glibc mallocs exactly this
constexpr std::uintptr_t kPage = 4096, kOldGlibcHeader = 16;

std::uintptr_t page_offset(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kPage; }
#endif

#if defined(JELLYSIM_TEST_ASAN)
/// A thread whose first use of the probe mallocs its own TLS block, placed so that it starts 16
/// bytes past a page boundary: it allocates blocks of the probe's size until the block `skip`
/// allocations after the next would start there, then touches the probe, and lives (its block in
/// its DTV, as Mesa's is during a run) until release(). Same-size allocations come from one size
/// class in address order; `skip` counts the allocations glibc makes of that class on the way to
/// the TLS block (none when run alone; one under CTest on this machine, measured).
class PlacedTlsBlock {
 public:
  PlacedTlsBlock(char* (*touch)(), std::intptr_t skip) {
    auto placed = std::make_shared<std::promise<const char*>>();
    std::future<const char*> block = placed->get_future();
    thread_ = std::thread([touch, skip, placed, released = release_.get_future()]() mutable {
      std::vector<void*> held{std::malloc(kProbeTlsBytes), std::malloc(kProbeTlsBytes)};
      const auto stride = [&] {
        return reinterpret_cast<std::intptr_t>(held.back()) - reinterpret_cast<std::intptr_t>(held[held.size() - 2]);
      };
      while (held.size() < 100000 &&
             page_offset(static_cast<char*>(held.back()) + (1 + skip) * stride()) != kOldGlibcHeader)
        held.push_back(std::malloc(kProbeTlsBytes));
      const char* b = touch();
      for (void* p : held) std::free(p);
      placed->set_value(b);
      released.wait();
    });
    block_ = block.get();
  }
  ~PlacedTlsBlock() {
    release_.set_value();
    thread_.join();
  }
  const char* block() const { return block_; }

 private:
  std::promise<void> release_;
  std::thread thread_;
  const char* block_ = nullptr;
};
#endif

TEST(SanitizerDefaults, LeakCheckSurvivesADynamicTlsBlockSixteenBytesPastAPage) {
#if !defined(JELLYSIM_TEST_ASAN)
  GTEST_SKIP() << "only meaningful under AddressSanitizer";
#else
  void* library = ::dlopen(JELLYSIM_TLS_PROBE_PATH, RTLD_NOW);
  ASSERT_NE(library, nullptr) << ::dlerror();
  auto touch = reinterpret_cast<char* (*)()>(::dlsym(library, "tls_probe_touch"));
  ASSERT_NE(touch, nullptr);
  for (std::intptr_t skip = 0; skip < 4; ++skip) {
    const PlacedTlsBlock probe(touch, skip);
    if (page_offset(probe.block()) != kOldGlibcHeader) continue;
    EXPECT_EQ(__lsan_do_recoverable_leak_check(), 0);  // dies here if the interceptor is on
    return;
  }
  FAIL() << "the TLS block did not land 16 bytes past a page in 4 placements";
#endif
}

}  // namespace
