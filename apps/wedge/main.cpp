// wedge: the command-line front end of the engine, one file per verb (inertia.cpp, simulate.cpp,
// collide.cpp, render.cpp, slice.cpp, import.cpp, replay.cpp). `wedge view` and `wedge xr` run the
// programs wedge-view and wedge-xr beside this one (program.hpp); exit codes in cli_error.hpp.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "cli_error.hpp"
#include "fp_traps.hpp"
#include "program.hpp"
#include "program_config.hpp"
#include "verbs.hpp"

namespace {

using namespace wedge::cli;

// Why this build has no program for the verb, if it has none by design (the build's options).
const char* missing_by_design([[maybe_unused]] const std::string& verb) {
#ifndef WEDGE_HAVE_VIEW
  if (verb == "view") return "it was built without the viewer (WEDGE_BUILD_VIEWER=OFF)";
#endif
#ifndef WEDGE_HAVE_XR
  if (verb == "xr") return "it was built without the OpenXR SDK (Debian: libopenxr-dev) or with WEDGE_BUILD_XR=OFF";
#endif
  return nullptr;
}

// Replaces this process with wedge-VERB from this program's folder, given the same arguments. Returns
// only if that cannot be done, with the exit code after saying why.
int run_verb_program(const std::string& verb, const char* argv0, std::vector<std::string> verb_args) {
  if (const char* why = missing_by_design(verb)) {
    std::cerr << "wedge: this build has no '" << verb << "' verb: " << why << "\n";
    return kExitBadInput;
  }
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path program = (ec ? std::filesystem::path(argv0) : self).parent_path() / ("wedge-" + verb);
  std::string name = program.string();
  std::vector<char*> args = {name.data()};
  for (std::string& a : verb_args) args.push_back(a.data());
  args.push_back(nullptr);
  ::execv(name.c_str(), args.data());
  const int err = errno;
  if (err == ENOENT) {
    std::cerr << "wedge: '" << verb << "' is the program wedge-" << verb << ", which is not built beside this one ("
              << name << "): build it with cmake --build BUILD --target wedge-" << verb << "\n";
    return kExitBadInput;
  }
  std::cerr << "wedge: cannot run " << name << ": " << std::strerror(err) << "\n";
  return kExitInternal;
}

}  // namespace

int main(int argc, char** argv) {
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
  CLI::App* inertia_cmd = add_inertia_verb(app, inertia);
  CLI::App* simulate_cmd = add_simulate_verb(app, simulate);
  CLI::App* collide_cmd = add_collide_verb(app, collide);
  CLI::App* render_cmd = add_render_verb(app, render);
  CLI::App* slice_cmd = add_slice_verb(app, slice);
  CLI::App* import_cmd = add_import_verb(app, import_options);
  CLI::App* replay_cmd = add_replay_verb(app, replay);
  // Listed in the help; run by their own programs.
  app.add_subcommand("view", kViewSummary)->allow_extras();
  app.add_subcommand("xr", kXrSummary)->allow_extras();

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
  if (!args.empty() && (args[0] == "view" || args[0] == "xr")) return run_verb_program(args[0], argv[0], args);
  if (!args.empty() && !args[0].empty() && args[0][0] != '-' &&
      std::find(verbs.begin(), verbs.end(), args[0]) == verbs.end()) {
    std::cerr << "wedge: unknown verb '" << args[0] << "' (the verbs are inertia, simulate, collide, render, "
              << "slice, import, replay, view and xr)\nRun 'wedge --help' for usage.\n";
    return kExitBadInput;
  }

  if (const std::optional<int> code = parse_verb_line(app, args)) return *code;
  return run_verb([&] {
    if (inertia_cmd->parsed()) return run_inertia(inertia);
    if (simulate_cmd->parsed()) return run_simulate(simulate);
    if (collide_cmd->parsed()) return run_collide(collide);
    if (render_cmd->parsed()) return run_render(render);
    if (slice_cmd->parsed()) return run_slice(slice);
    if (import_cmd->parsed()) return run_import(import_options);
    if (replay_cmd->parsed()) return run_replay(replay);
    std::cerr << "wedge: no verb given\n";
    return kExitBadInput;
  });
}
