// The floating-point environment around arithmetic whose exceptions are expected and handled by the code
// that runs it. Parsing untrusted text is the case: strtod raises overflow for "1e999" by design, and the
// caller reports it as bad input. Under floating-point traps (the tests turn them on, tests/main.cpp) such
// an exception must not stop the program, and with or without traps its flags must not leak into the
// caller's state.
#pragma once

#include <cfenv>

namespace wedge {

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
