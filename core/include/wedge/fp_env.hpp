// Floating-point traps, and the environment around arithmetic whose exceptions are expected and handled
// by the code that runs it.
//
// Trapped (the tests turn the traps on, tests/main.cpp; the program on request, apps/wedge/fp_traps.hpp):
// invalid operations (0/0, inf - inf, sqrt(-1)), division by zero and overflow raise SIGFPE at the
// faulting instruction, so a NaN or an infinity born in a step stops the program at its source. Underflow
// and inexact stay off: gradual underflow and rounding are ordinary arithmetic.
//
// Expected exceptions: Parsing untrusted text is the case: strtod raises overflow for "1e999" by design, and the
// caller reports it as bad input. Under floating-point traps (the tests turn them on, tests/main.cpp) such
// an exception must not stop the program, and with or without traps its flags must not leak into the
// caller's state.
#pragma once

#include <cfenv>

namespace wedge {

inline constexpr int kTrappedFpExceptions = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;

// Traps on for kTrappedFpExceptions from here on, with the flags raised so far cleared (glibc's
// feenableexcept).
inline void trap_fp_exceptions() {
  std::feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(kTrappedFpExceptions);
}

// For its lifetime: exception flags cleared and traps off (C's feholdexcept); on exit the environment is
// put back as it was (fesetenv), traps and flags included.
class ExpectedFpExceptions {
 public:
  ExpectedFpExceptions() { std::feholdexcept(&saved_); }
  ~ExpectedFpExceptions() { std::fesetenv(&saved_); }
  ExpectedFpExceptions(const ExpectedFpExceptions&) = delete;
  ExpectedFpExceptions& operator=(const ExpectedFpExceptions&) = delete;

 private:
  std::fenv_t saved_;
};

}  // namespace wedge
