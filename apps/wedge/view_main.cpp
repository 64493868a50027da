// wedge-view: the desktop viewer, what `wedge view` runs (program.hpp; the verb is view.cpp).
#include "fp_traps.hpp"
#include "program.hpp"
#include "verbs.hpp"

int main(int argc, char** argv) {
  using namespace wedge::cli;
  enable_fp_traps_if_requested();  // WEDGE_FP_TRAPS=1 (fp_traps.hpp)
  return run_one_verb_program<ViewOptions>(argc, argv, "view", add_view_verb, run_view);
}
