// wedge: the command-line front end of the engine. Dispatches to one verb per file (inertia.cpp,
// simulate.cpp, collide.cpp, render.cpp, slice.cpp); exit codes in cli_error.hpp.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "cli_error.hpp"
#include "verbs.hpp"
#include "wedge/error.hpp"

int main(int argc, char** argv) {
  using namespace wedge::cli;
  CLI::App app{"wedge: n-dimensional rigid-body dynamics (n = 2..6) with geometric algebra.\n"
               "Input and output formats: docs/scene-format.md.",
               "wedge"};
  app.require_subcommand(1);
  app.footer(std::string("Run 'wedge VERB --help' for the options of a verb.\n") + kExitCodesText);

  InertiaOptions inertia;
  SimulateOptions simulate;
  CollideOptions collide;
  RenderOptions render;
  SliceOptions slice;
  CLI::App* inertia_cmd = add_inertia_verb(app, inertia);
  CLI::App* simulate_cmd = add_simulate_verb(app, simulate);
  CLI::App* collide_cmd = add_collide_verb(app, collide);
  CLI::App* render_cmd = add_render_verb(app, render);
  CLI::App* slice_cmd = add_slice_verb(app, slice);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // prints the help of the (sub)command asked for, exit code 0
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "wedge: " << e.what() << "\nRun 'wedge --help' for usage.\n";
    return kExitBadInput;
  }

  try {
    if (inertia_cmd->parsed()) return run_inertia(inertia);
    if (simulate_cmd->parsed()) return run_simulate(simulate);
    if (collide_cmd->parsed()) return run_collide(collide);
    if (render_cmd->parsed()) return run_render(render);
    if (slice_cmd->parsed()) return run_slice(slice);
    std::cerr << "wedge: no verb given\n";
    return kExitBadInput;
  } catch (const Failure& e) {
    std::cerr << "wedge: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const wedge::Error& e) {  // should have been caught with a file name; still bad input
    std::cerr << "wedge: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "wedge: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}
