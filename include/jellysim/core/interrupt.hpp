#pragma once
// SIGINT / SIGTERM / SIGHUP as a request to stop (issue 23): the first signal is recorded and the
// run loops stop at their next step boundary, keeping what they computed (summary.json status
// "interrupted", exit 128 + signal); a second signal ends the process at once. Child programs
// (ffmpeg) run in process groups of their own, so a terminal's Ctrl-C reaches jellysim alone.
#include <string>

namespace jellysim::core {

/// Installs the handlers for SIGINT, SIGTERM and SIGHUP, and ignores SIGPIPE (a write to a closed
/// pipe fails with EPIPE instead); once per process, the CLI does it at start.
void install_interrupt_handlers();
/// The signal that asked the process to stop (SIGINT, SIGTERM, SIGHUP), or 0.
int interrupt_signal();
/// "SIGINT" / "SIGTERM" / "SIGHUP" / "signal N".
std::string signal_name(int signal_number);
/// Records a stop request as the handler would (tests).
void request_interrupt(int signal_number);
/// Forgets a stop request (tests).
void clear_interrupt();

}  // namespace jellysim::core
