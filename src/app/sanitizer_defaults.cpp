// Default AddressSanitizer options, linked into every program of the project (the command line and
// each test program); compiles to nothing in builds without AddressSanitizer.
//
// intercept_tls_get_addr=0: up to GCC 13 / LLVM 16, the runtime's __tls_get_addr interceptor
// assumes a dynamic TLS block whose address is 16 bytes past a page boundary carries the header of
// glibc < 2.25 and reads the two words before it as the block's start and size. Since glibc 2.25
// (Debian 12 has 2.36) these blocks come from malloc, so the guess is wrong whenever malloc happens
// to return such an address, which depends only on how many allocations came before. LeakSanitizer
// then scans a bogus range and its stop-the-world tracer dies ("Tracer caught signal 11",
// google/sanitizers#1353; fixed upstream in LLVM 17 by asking the allocator instead). Mesa's
// OpenGL driver has such blocks, and `jellysim run` hit one in both CI runs of 2026-11-21/22.
// Without the interceptor the leak check still follows glibc's blocks, which are ordinary heap
// chunks reachable from the thread's dynamic thread vector (the whole suite passes unchanged).
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define JELLYSIM_ADDRESS_SANITIZER 1
#elif defined(__has_feature)  // Clang
#if __has_feature(address_sanitizer)
#define JELLYSIM_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(JELLYSIM_ADDRESS_SANITIZER)
extern "C" __attribute__((visibility("default"), used)) const char* __asan_default_options() {
  return "intercept_tls_get_addr=0";
}
#endif
