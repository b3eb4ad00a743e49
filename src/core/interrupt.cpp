#include "jellysim/core/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace jellysim::core {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs a lock-free flag");

// Async-signal-safe: an atomic store, or _exit on the second signal.
extern "C" void on_interrupt(int signal_number) {
  int expected = 0;
  if (!g_signal.compare_exchange_strong(expected, signal_number)) ::_exit(128 + signal_number);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write in progress completes; the loops poll the flag
  // SIGHUP too: a closed terminal or SSH session ends the run as Ctrl-C does, with its summary.
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
  // A closed standard output (`jellysim batch ... | head -1`) fails the write (EPIPE: the stream
  // stops printing) instead of killing the process mid-run.
  ::signal(SIGPIPE, SIG_IGN);
}

int interrupt_signal() { return g_signal.load(std::memory_order_relaxed); }

std::string signal_name(int signal_number) {
  if (signal_number == SIGINT) return "SIGINT";
  if (signal_number == SIGTERM) return "SIGTERM";
  if (signal_number == SIGHUP) return "SIGHUP";
  return "signal " + std::to_string(signal_number);
}

void request_interrupt(int signal_number) { g_signal.store(signal_number); }
void clear_interrupt() { g_signal.store(0); }

}  // namespace jellysim::core
