#pragma once
// LeakSanitizer's end-of-process check, run early (sanitizer builds only; a no-op otherwise).
//
// The check normally runs from an exit handler, after Mesa's own exit handler has begun stopping
// the OpenGL driver's worker threads. Its stop-the-world tracer can crash on a thread that is
// exiting under it ("Tracer caught signal 11", google/sanitizers#1353), failing a sound run. Called
// at the end of main (the command line) or of the test run, the check sees every thread parked;
// it then reports exactly what the exit-time check would, and does not run again at exit.
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define JELLYSIM_ADDRESS_SANITIZER 1
#elif defined(__has_feature)  // Clang
#if __has_feature(address_sanitizer)
#define JELLYSIM_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(JELLYSIM_ADDRESS_SANITIZER)
#include <sanitizer/lsan_interface.h>
#endif

namespace jellysim::app {

inline void check_leaks_before_exit() {
#if defined(JELLYSIM_ADDRESS_SANITIZER)
  __lsan_do_leak_check();
#endif
}

}  // namespace jellysim::app
