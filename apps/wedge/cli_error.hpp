// Errors of the `wedge` program and its exit codes.
//
// Exit codes: 0 success; 2 bad input (unreadable or invalid file, bad option, usage error, a simulation
// that would produce a non-finite value); 3 an internal error (a bug in wedge: the message asks for a
// report); 128 + the signal number when interrupted (130 for Ctrl-C). Every failure prints one message on
// stderr and leaves no output file behind.
#pragma once

#include <stdexcept>
#include <string>

namespace wedge::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInternal = 3;
inline constexpr const char* kExitCodesText =
    "Exit codes: 0 success, 2 bad input or usage, 3 internal error (please report it), 130 interrupted (Ctrl-C).";

// Something that should never happen whatever the input: a bug in wedge, reported as such (exit 3).
class InternalError : public std::runtime_error {
 public:
  explicit InternalError(const std::string& what) : std::runtime_error(what) {}
};

// A complete, user-facing message (already prefixed with the file name where there is one). The scene
// library's wedge::scenes::SceneError is one too; main() reports both the same way.
class Failure : public std::runtime_error {
 public:
  explicit Failure(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace wedge::cli
