// A shared library with a thread-local buffer, for tests/app/test_sanitizer_defaults.cpp: glibc
// gives a dlopen'ed library's TLS its own malloc'd block on first use (dynamic TLS), as Mesa's has.
thread_local char tls_probe_buffer[24];

extern "C" __attribute__((visibility("default"))) char* tls_probe_touch() {
  ++tls_probe_buffer[0];
  return tls_probe_buffer;
}
