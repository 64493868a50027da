// Running the `wedge` program as a user would, for the CLI tests: a fresh temporary folder per test
// case, input files written into it, the binary run through the shell there, stdout, stderr and the
// exit code captured.
#pragma once

#include <catch2/catch.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace cli_runner {

namespace fs = std::filesystem;
using nlohmann::json;

// The program under test: this build's, or WEDGE_PROGRAM's (tools/check.sh runs these tests against the
// ASan + UBSan build of the program so).
inline const std::string kWedge = [] {
  const char* program = std::getenv("WEDGE_PROGRAM");
  return program != nullptr && *program != '\0' ? std::string(program) : std::string(WEDGE_BINARY_DIR "/apps/wedge/wedge");
}();

struct Result {
  int code = -1;
  std::string out, err;
  std::vector<json> lines() const {
    std::vector<json> v;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) v.push_back(json::parse(line));
    return v;
  }
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh temporary folder per test case, removed at the end.
class TempDir {
 public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "wedge_cli_test_XXXXXX").string();
    REQUIRE(::mkdtemp(templ.data()) != nullptr);
    path_ = templ;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  // Runs `wedge ARGS` in this folder (so file names in messages are the short names given).
  Result run(const std::string& args) const { return capture("'" + kWedge + "' " + args); }
  // Runs a shell script in this folder with $WEDGE naming the program (for signals and pipes).
  Result shell(const std::string& script) const { return capture("WEDGE='" + kWedge + "' sh -c '" + script + "'"); }
  // The names in the folder (without the captured outputs).
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  // Runs the command in this folder, capturing stdout, stderr and the exit code.
  Result capture(const std::string& command) const {
    const std::string out = (path_ / ".stdout").string(), err = (path_ / ".stderr").string();
    // WEDGE_FP_TRAPS=1: the program runs with floating-point traps on, as the tests do (tests/main.cpp),
    // unless the environment says 0.
    const std::string cmd = "cd '" + path_.string() + "' && export WEDGE_FP_TRAPS=${WEDGE_FP_TRAPS:-1} && " + command +
                            " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_file(out);
    r.err = read_file(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  fs::path path_;
};

}  // namespace cli_runner
