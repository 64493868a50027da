// wedge: the command-line front end of the engine. Dispatches to one verb per file (inertia.cpp,
// simulate.cpp, collide.cpp, render.cpp, slice.cpp, import.cpp, replay.cpp, view.cpp); exit codes in cli_error.hpp.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli_error.hpp"
#include "wedge/scenes/error.hpp"
#include "fp_traps.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"
#include "wedge/error.hpp"

int main(int argc, char** argv) {
  using namespace wedge::cli;
  enable_fp_traps_if_requested();  // WEDGE_FP_TRAPS=1 (fp_traps.hpp)
  CLI::App app{"wedge: n-dimensional rigid-body dynamics (n = 2..6) with geometric algebra.\n"
               "Input and output formats: docs/scene-format.md.",
               "wedge"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("wedge ") + WEDGE_VERSION);
  app.footer(std::string("Run 'wedge VERB --help' (or 'wedge help VERB') for the options of a verb.\n") +
             kExitCodesText);

  InertiaOptions inertia;
  SimulateOptions simulate;
  CollideOptions collide;
  RenderOptions render;
  SliceOptions slice;
  ImportOptions import_options;
  ReplayOptions replay;
  ViewOptions view;
  CLI::App* inertia_cmd = add_inertia_verb(app, inertia);
  CLI::App* simulate_cmd = add_simulate_verb(app, simulate);
  CLI::App* collide_cmd = add_collide_verb(app, collide);
  CLI::App* render_cmd = add_render_verb(app, render);
  CLI::App* slice_cmd = add_slice_verb(app, slice);
  CLI::App* import_cmd = add_import_verb(app, import_options);
  CLI::App* replay_cmd = add_replay_verb(app, replay);
  CLI::App* view_cmd = add_view_verb(app, view);
#ifdef WEDGE_HAVE_XR
  XrOptions xr;
  CLI::App* xr_cmd = add_xr_verb(app, xr);
#endif

  // The verb comes first. Name an unknown one (CLI11 would only say that a subcommand is required), and
  // take `wedge help [VERB]` as the --help it means.
  const std::vector<std::string> verbs = {"inertia", "simulate", "collide", "render", "slice",
                                          "import",  "replay",   "view",    "xr"};
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "help") {
    if (args.size() == 1) {
      std::cout << app.help();
      return kExitOk;
    }
    args = {args[1], "--help"};
  }
#ifndef WEDGE_HAVE_XR
  if (!args.empty() && args[0] == "xr") {
    std::cerr << "wedge: this build has no 'xr' verb: it was built without the OpenXR SDK (Debian: libopenxr-dev)\n";
    return kExitBadInput;
  }
#endif
  if (!args.empty() && !args[0].empty() && args[0][0] != '-' &&
      std::find(verbs.begin(), verbs.end(), args[0]) == verbs.end()) {
    std::cerr << "wedge: unknown verb '" << args[0] << "' (the verbs are inertia, simulate, collide, render, "
              << "slice, import, replay, view and xr)\nRun 'wedge --help' for usage.\n";
    return kExitBadInput;
  }

  try {
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments as a stack, last first
    app.parse(args);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // prints the help of the (sub)command asked for, exit code 0
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "wedge: " << e.what() << "\nRun 'wedge --help' for usage.\n";
    return kExitBadInput;
  }

  install_interrupt_handlers();
  try {
    if (inertia_cmd->parsed()) return run_inertia(inertia);
    if (simulate_cmd->parsed()) return run_simulate(simulate);
    if (collide_cmd->parsed()) return run_collide(collide);
    if (render_cmd->parsed()) return run_render(render);
    if (slice_cmd->parsed()) return run_slice(slice);
    if (import_cmd->parsed()) return run_import(import_options);
    if (replay_cmd->parsed()) return run_replay(replay);
    if (view_cmd->parsed()) return run_view(view);
#ifdef WEDGE_HAVE_XR
    if (xr_cmd->parsed()) return run_xr(xr);
#endif
    std::cerr << "wedge: no verb given\n";
    return kExitBadInput;
  } catch (const Interrupted& e) {
    std::cerr << "wedge: " << e.what() << "\n";
    return 128 + e.signal();
  } catch (const Failure& e) {
    std::cerr << "wedge: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const wedge::scenes::SceneError& e) {
    std::cerr << "wedge: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const wedge::Error& e) {  // should have been caught with a file name; still bad input
    std::cerr << "wedge: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {  // InternalError, std::bad_alloc, ...
    std::cerr << "wedge: internal error: " << e.what()
              << "\nThis is a bug in wedge: please report it with the command line and the input files.\n";
    return kExitInternal;
  }
}
