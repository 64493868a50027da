#include "interrupt.hpp"

#include <csignal>
#include <string>

namespace wedge::cli {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) { g_signal = sig; }

}  // namespace

Interrupted::Interrupted(int sig)
    : std::runtime_error(std::string("interrupted (") + (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP") +
                         "); partial output removed"),
      signal_(sig) {}

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second signal takes the default action: the process ends at once
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
}

int interrupt_signal() { return int(g_signal); }

void throw_if_interrupted() {
  if (g_signal != 0) throw Interrupted(int(g_signal));
}

}  // namespace wedge::cli
