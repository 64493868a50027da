// Floating-point traps for the tests (tests/main.cpp turns them on; wedge/fp_env.hpp says which).
#pragma once

#include <cstdlib>
#include <cstring>

#include "wedge/fp_env.hpp"

namespace fp_traps {

// Unless WEDGE_FP_TRAPS=0 (tests/main.cpp says when).
inline bool requested() {
  const char* value = std::getenv("WEDGE_FP_TRAPS");
  return value == nullptr || std::strcmp(value, "0") != 0;
}

// The traps off for a scope, for a library that computes with infinities on purpose (Mesa); the flags it
// raises are dropped on the way out, so they do not leak into the code under test.
using Suspended = wedge::ExpectedFpExceptions;

}  // namespace fp_traps
