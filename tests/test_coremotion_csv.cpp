// The CoreMotion CSV reader (recordings/coremotion_csv.hpp): the shipped trace reads whole and means what
// its README says (869 samples over 9.36 s at ~93 Hz; CoreMotion's gravity is a unit vector in g), and
// bad files are refused with the file, the line and the problem.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "wedge/error.hpp"
#include "wedge/recordings/coremotion_csv.hpp"

using wedge::recordings::read_coremotion_csv;

TEST_CASE("CoreMotion CSV: the shipped kinetic-tremor trace", "[recordings]") {
  const auto s = read_coremotion_csv(std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor_data.csv");
  REQUIRE(s.size() == 869);
  CHECK(s.front().time == 0.0);
  CHECK(s.back().time == Approx(9.356071250047535).epsilon(1e-15));
  for (const auto& x : s) CHECK(x.gravity.norm() == Approx(1.0).margin(1e-3));  // unit g, to float precision
  // The first row, column by column (the header's order is not the struct's).
  CHECK(s.front().gravity.x() == -0.36853873729705805);
  CHECK(s.front().user_acceleration.z() == 0.08698909729719162);
  CHECK(s.front().rotation_rate.y() == -0.047954745590686805);
}

TEST_CASE("CoreMotion CSV: bad files name the file, the line and the problem", "[recordings]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wedge_coremotion_test";
  std::filesystem::create_directories(dir);
  const std::string header =
      "timestamp,gravity.x,gravity.y,gravity.z,userAcceleration.x,userAcceleration.y,userAcceleration.z,"
      "rotationRate.x,rotationRate.y,rotationRate.z\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty file"},
      {"timestamp,gravity.x\n0,1\n", "line 1: no column 'gravity.y'"},
      {header + "0,0,0,-1,0,0,0,0,0,0\n0.01,0,0,-1,0,0,x,0,0,0\n", "line 3: userAcceleration.z is not a finite number"},
      {header + "0,0,0,-1,0,0,0,0,0\n", "line 2: 9 fields, the header has 10"},
      {header + "1,0,0,-1,0,0,0,0,0,0\n0.5,0,0,-1,0,0,0,0,0,0\n", "line 3: timestamp goes backwards"},
      {header, "no samples"},
  };
  for (const auto& [text, message] : cases) {
    const std::string path = (dir / "bad.csv").string();
    std::ofstream(path) << text;
    INFO(text);
    try {
      read_coremotion_csv(path);
      FAIL("no error");
    } catch (const wedge::Error& e) {
      CHECK(std::string(e.what()).find(path) == 0);
      CHECK(std::string(e.what()).find(message) != std::string::npos);
    }
  }
  CHECK_THROWS_AS(read_coremotion_csv((dir / "missing.csv").string()), wedge::Error);
  std::filesystem::remove_all(dir);
}
