// The test runner: Catch2's, with floating-point traps on (wedge/fp_env.hpp), so a NaN or an infinity born
// anywhere in a step fails the test at its source instead of surfacing later as a wrong number.
// Third-party code that computes with infinities on purpose runs inside fp_traps::Suspended
// (support/fp_traps.hpp).
//
// WEDGE_FP_TRAPS=0 leaves the traps off, here and in the programs the tests run. The clang sanitizer
// build sets it (tools/check.sh): clang assumes floating-point operations never trap and vectorises a
// scalar division as a packed one whose unused lane divides 0 by 0, which a trap cannot tell from a real
// invalid operation. GCC keeps -ftrapping-math, so the Release build runs with the traps on.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "fp_traps.hpp"

int main(int argc, char* argv[]) {
  if (fp_traps::requested()) wedge::trap_fp_exceptions();
  return Catch::Session().run(argc, argv);
}
