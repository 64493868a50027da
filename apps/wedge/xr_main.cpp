// wedge-xr: the scenes in a headset through OpenXR, what `wedge xr` runs (program.hpp; the verb is xr.cpp).
#include "fp_traps.hpp"
#include "program.hpp"
#include "verbs.hpp"

int main(int argc, char** argv) {
  using namespace wedge::cli;
  enable_fp_traps_if_requested();  // WEDGE_FP_TRAPS=1 (fp_traps.hpp)
  return run_one_verb_program<XrOptions>(argc, argv, "xr", add_xr_verb, run_xr);
}
