// Floating-point traps in the program, on request: WEDGE_FP_TRAPS=1 (the tests set it for every run,
// tests/support/cli_runner.hpp; docs/testing.md). Invalid operations, division by zero and overflow then
// raise SIGFPE where they happen, so a NaN or an infinity born in a step stops the program at its source.
//
// Mesa's software rasteriser (OSMesa, and GLX on llvmpipe) computes with infinities on purpose, from its
// context's creation on. The verbs that draw therefore run their drawing with traps off (MesaArithmetic)
// and turn them back on around the world's steps (TrappedSteps).
#pragma once

#include <cfenv>
#include <cstdlib>
#include <cstring>

#include "wedge/fp_env.hpp"

namespace wedge::cli {

inline bool fp_traps_requested() {
  static const bool requested = [] {
    const char* value = std::getenv("WEDGE_FP_TRAPS");
    return value != nullptr && std::strcmp(value, "1") == 0;
  }();
  return requested;
}

// For the whole program (main).
inline void enable_fp_traps_if_requested() {
  if (fp_traps_requested()) trap_fp_exceptions();
}

// Traps off and flags kept apart while Mesa draws; the environment is restored on exit.
using MesaArithmetic = ExpectedFpExceptions;

// Traps back on (when requested) while the world steps inside a drawing verb; restored on exit.
class TrappedSteps {
 public:
  TrappedSteps() : on_(fp_traps_requested()) {
    if (!on_) return;
    std::fegetenv(&saved_);
    trap_fp_exceptions();  // (flags Mesa left behind are not the steps')
  }
  ~TrappedSteps() {
    if (on_) std::fesetenv(&saved_);
  }
  TrappedSteps(const TrappedSteps&) = delete;
  TrappedSteps& operator=(const TrappedSteps&) = delete;

 private:
  bool on_;
  std::fenv_t saved_{};
};

}  // namespace wedge::cli
