// Ctrl-C (SIGINT), SIGTERM and SIGHUP: the handler only sets a flag; the verbs poll it between steps and
// frames and throw Interrupted, so the usual unwinding removes temporary files and partial frame sets
// (OutputSink's destructor, render's clean-up) before main exits with 128 + the signal number. A second
// signal kills at once (the handler is reset after the first).
#pragma once

#include <stdexcept>

namespace wedge::cli {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

void install_interrupt_handlers();
// Throws Interrupted once a signal has arrived.
void throw_if_interrupted();
// The signal that arrived (SIGINT, SIGTERM, SIGHUP), or 0: for loops that end cleanly on one (wedge xr).
int interrupt_signal();

}  // namespace wedge::cli
