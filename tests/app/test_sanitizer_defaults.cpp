// The sanitized programs' default options (src/app/sanitizer_defaults.cpp) keep LeakSanitizer
// working when a dynamic TLS block lands 16 bytes past a page boundary. With GCC 12's runtime and
// its __tls_get_addr interceptor on, the leak check below dies in the tracer ("Tracer caught
// signal 11"), as `jellysim run` did on the CI machine with one of Mesa's blocks.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <dlfcn.h>
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

TEST(SanitizerDefaults, LeakCheckSurvivesADynamicTlsBlockSixteenBytesPastAPage) {
#if !defined(JELLYSIM_TEST_ASAN)
  GTEST_SKIP() << "only meaningful under AddressSanitizer";
#else
  void* library = ::dlopen(JELLYSIM_TLS_PROBE_PATH, RTLD_NOW);
  ASSERT_NE(library, nullptr) << ::dlerror();
  auto touch = reinterpret_cast<char* (*)()>(::dlsym(library, "tls_probe_touch"));
  ASSERT_NE(touch, nullptr);
  // Same-size allocations come from one size class in address order: learn the stride, then
  // allocate until the next block of this size would start 16 bytes past a page boundary.
  std::vector<void*> held{std::malloc(kProbeTlsBytes), std::malloc(kProbeTlsBytes)};
  auto stride = [&] {
    return reinterpret_cast<std::intptr_t>(held.back()) - reinterpret_cast<std::intptr_t>(held[held.size() - 2]);
  };
  while (held.size() < 100000 &&
         page_offset(static_cast<char*>(held.back()) + stride()) != kOldGlibcHeader)
    held.push_back(std::malloc(kProbeTlsBytes));
  const char* block = touch();  // glibc mallocs the probe's TLS block now
  for (void* p : held) std::free(p);
  ASSERT_EQ(page_offset(block), kOldGlibcHeader) << "the TLS block did not land where intended";
  EXPECT_EQ(__lsan_do_recoverable_leak_check(), 0);  // dies here if the interceptor is on
#endif
}

}  // namespace
