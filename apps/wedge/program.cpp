#include "program.hpp"

#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include "cli_error.hpp"
#include "interrupt.hpp"
#include "wedge/error.hpp"
#include "wedge/scenes/error.hpp"

namespace wedge::cli {

namespace {
// The message on one line, whatever it quotes: line breaks written as \n and \r. The libraries quote a
// user's keys and fields through wedge::printable; this is the last guard before the terminal.
std::string one_line(const std::string& message) {
  std::string out;
  for (const char c : message) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else {
      out += c;
    }
  }
  return out;
}
}  // namespace

std::optional<int> parse_verb_line(CLI::App& app, std::vector<std::string> args) {
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
    std::cerr << "wedge: " << one_line(e.what()) << "\nRun 'wedge --help' for usage.\n";
    return kExitBadInput;
  }
  return std::nullopt;
}

int run_verb(const std::function<int()>& verb) {
  install_interrupt_handlers();
  try {
    return verb();
  } catch (const Interrupted& e) {
    std::cerr << "wedge: " << one_line(e.what()) << "\n";
    return 128 + e.signal();
  } catch (const Failure& e) {
    std::cerr << "wedge: " << one_line(e.what()) << "\n";
    return kExitBadInput;
  } catch (const scenes::SceneError& e) {
    std::cerr << "wedge: " << one_line(e.what()) << "\n";
    return kExitBadInput;
  } catch (const wedge::Error& e) {  // should have been caught with a file name; still bad input
    std::cerr << "wedge: " << one_line(e.what()) << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {  // InternalError, std::bad_alloc, ...
    std::cerr << "wedge: internal error: " << one_line(e.what())
              << "\nThis is a bug in wedge: please report it with the command line and the input files.\n";
    return kExitInternal;
  }
}

}  // namespace wedge::cli
