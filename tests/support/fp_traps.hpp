// Floating-point traps for the tests (tests/main.cpp turns them on): FE_INVALID, FE_DIVBYZERO and
// FE_OVERFLOW raise SIGFPE at the faulting instruction (glibc's feenableexcept).
#pragma once

#include <cfenv>
#include <cstdlib>
#include <cstring>

namespace fp_traps {

constexpr int kTrapped = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;

// Unless WEDGE_FP_TRAPS=0 (tests/main.cpp says when).
inline bool requested() {
  const char* value = std::getenv("WEDGE_FP_TRAPS");
  return value == nullptr || std::strcmp(value, "0") != 0;
}

inline void enable() {
  std::feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(kTrapped);
}

// The traps off for a scope, for a library that computes with infinities on purpose; the flags it raises
// are cleared on the way out so they do not leak into the code under test.
class Suspended {
 public:
  Suspended() : was_(fegetexcept()) { fedisableexcept(kTrapped); }
  ~Suspended() {
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(was_);
  }
  Suspended(const Suspended&) = delete;
  Suspended& operator=(const Suspended&) = delete;

 private:
  int was_;
};

}  // namespace fp_traps
