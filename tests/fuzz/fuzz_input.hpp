// What every fuzz target shares: the input written to a file (the parsers read files, as the program
// does), the verb run exactly as `wedge` runs it, and the verdict. Bad input must end in a Failure or a
// scenes::SceneError (the program's exit 2 with one line naming the file); any other exception is what the
// program would report as an internal error (exit 3), so it aborts the fuzzer as a finding, as does any
// crash, hang, leak or sanitizer report.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_error.hpp"
#include "wedge/scenes/error.hpp"
#include "wedge/error.hpp"

namespace fuzz {

// A folder of this process's own, removed at exit.
inline const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("wedge_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] { std::filesystem::remove_all(work_dir()); });
    return d;
  }();
  return dir;
}

// Writes the input to `name` in the work folder; returns its path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string path = (work_dir() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}


// Runs `verb` on the input at `path`. The expected refusal of bad input is a Failure or a SceneError whose
// message is one line naming the file (what `wedge` prints before exit 2). Anything else thrown is a finding: a
// wedge::Error that escaped without the file's name, or another exception (the program's exit 3).
inline void expect_one_line_naming(const std::string& path, const std::exception& e) {
  const std::string what = e.what();
  if (what.find(path) == std::string::npos || what.find('\n') != std::string::npos) {
    std::fprintf(stderr, "fuzz: a refusal that is not one line naming %s: %s\n", path.c_str(), e.what());
    std::abort();
  }
}

template <class F>
void expect_success_or_refusal(const std::string& path, F&& verb) {
  try {
    verb();
  } catch (const wedge::cli::Failure& e) {
    expect_one_line_naming(path, e);
  } catch (const wedge::scenes::SceneError& e) {
    expect_one_line_naming(path, e);
  } catch (const wedge::Error& e) {
    std::fprintf(stderr, "fuzz: wedge::Error escaped without the file's name: %s\n", e.what());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: not a clear refusal (the program would exit 3): %s\n", e.what());
    std::abort();
  }
}

}  // namespace fuzz

// libFuzzer's start-up hook: the verbs print their results; keep the fuzzer's output to its findings.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (std::freopen("/dev/null", "w", stdout) == nullptr) std::abort();
  return 0;
}
