// What the wedge programs share. `wedge` runs the headless verbs itself; `wedge view` and `wedge xr` run
// the programs wedge-view and wedge-xr beside it (each its own build target, so that building `wedge`
// compiles no window or OpenXR code), as git runs git-VERB. All three read the verb first and end the
// same way: the exit codes and one-line messages of cli_error.hpp.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace wedge::cli {

// Parses args (the verb first, as given after the program's name) into app. Returns the exit code when
// the run ends here: 0 after --help or --version (printed), 2 after a usage error (named on stderr);
// nullopt when a verb is to run.
std::optional<int> parse_verb_line(CLI::App& app, std::vector<std::string> args);

// Runs a verb with Ctrl-C caught (interrupt.hpp) and its errors reported: one line on stderr and the
// exit code of cli_error.hpp (2 bad input, 3 internal error, 128 + the signal when interrupted).
int run_verb(const std::function<int()>& verb);

// wedge-view and wedge-xr: one verb, given first or left out ("wedge-view scene.json" is "wedge view
// scene.json").
template <class Options, class Add, class Run>
int run_one_verb_program(int argc, char** argv, const std::string& verb, Add add_verb, Run run) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] != verb) args.insert(args.begin(), verb);
  CLI::App app{"wedge " + verb, "wedge"};
  app.require_subcommand(1);
  Options options;
  add_verb(app, options);
  if (const std::optional<int> code = parse_verb_line(app, args)) return *code;
  return run_verb([&] { return run(options); });
}

}  // namespace wedge::cli
