// The CoreMotion CSV reader (recordings/coremotion_csv.hpp): the shipped trace reads whole and means what
// its README says (869 samples over 9.36 s at ~93 Hz; CoreMotion's gravity is a unit vector in g), and
// bad files are refused with the file, the line and the problem.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "csv_dialects.hpp"
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

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

// RFC 4180 as real tools write it: R's write.csv (the defect: quoted header names and a row-name
// column), a spreadsheet (byte-order mark, CRLF, no final newline), every field quoted with a free-text
// column of commas, quotes and line breaks. Each must read to the plain file's samples, bit for bit.
TEST_CASE("CoreMotion CSV: the dialects real tools write read to the same samples", "[recordings]") {
  const std::string plain_path = std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor_data.csv";
  const auto plain = read_coremotion_csv(plain_path);
  const std::string text = read_text(plain_path);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wedge_coremotion_dialects";
  std::filesystem::create_directories(dir);
  const std::pair<const char*, std::string> dialects[] = {
      {"R write.csv", csv_dialects::r_write_csv(text)},
      {"spreadsheet", csv_dialects::spreadsheet(text)},
      {"quoted with notes", csv_dialects::quoted_everywhere(text, true)},
  };
  for (const auto& [name, written] : dialects) {
    INFO(name);
    REQUIRE(written != text);
    const std::string path = (dir / "dialect.csv").string();
    std::ofstream(path, std::ios::binary) << written;
    const auto read = read_coremotion_csv(path);
    REQUIRE(read.size() == plain.size());
    int differ = 0;
    for (std::size_t i = 0; i < read.size(); ++i)
      differ += read[i].time != plain[i].time || read[i].gravity != plain[i].gravity ||
                read[i].user_acceleration != plain[i].user_acceleration || read[i].rotation_rate != plain[i].rotation_rate;
    CHECK(differ == 0);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("CoreMotion CSV: bad files name the file, the line and the problem", "[recordings]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wedge_coremotion_test";
  std::filesystem::create_directories(dir);
  const std::string header =
      "timestamp,gravity.x,gravity.y,gravity.z,userAcceleration.x,userAcceleration.y,userAcceleration.z,"
      "rotationRate.x,rotationRate.y,rotationRate.z\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty file"},
      {"timestamp,gravity.x\n0,1\n", ":1: no column 'gravity.y'"},
      {header + "0,0,0,-1,0,0,0,0,0,0\n0.01,0,0,-1,0,0,x,0,0,0\n", ":3: userAcceleration.z is not a finite number"},
      {header + "0,0,0,-1,0,0,0,0,0\n", ":2: 9 fields, the header has 10"},
      {header + "1,0,0,-1,0,0,0,0,0,0\n0.5,0,0,-1,0,0,0,0,0,0\n", ":3: timestamp goes backwards"},
      {header, "no samples"},
      {header + "0,0,0,-1,0,0,0,0,0,0\n\"0.01,0,0,-1,0,0,0,0,0,0\n", ":3: a quoted field is still open at the end"},
      {header + "0,0,0,-1,0,0,0,0,0,0\n0.01,0,0,\"-1\"x,0,0,0,0,0,0\n", ":3: malformed CSV quoting"},
      {header + "0,0,0,-1,0,0,0,0,0,0\n0.01,0,0,-1,0,0,0,0,0,0\n0.02,0,0,-1,0,0,0,0,0,\"0.5\"\n", ""},
      {header + "0,0,0,-1,0,0,0,0,0,0\n0.01,0,0,-1,0,0,0,\"1,5\",0,0\n", ":3: rotationRate.x is not a finite number ('1,5')"},
      {header + std::string("0,0,0,-1,\0,0,0,0,0,0\n", 21), ":2: a NUL byte"},
  };
  for (const auto& [text, message] : cases) {
    const std::string path = (dir / "bad.csv").string();
    std::ofstream(path) << text;
    INFO(text);
    if (message.empty()) {  // a quoted number is a number
      CHECK(read_coremotion_csv(path).back().rotation_rate.z() == 0.5);
      continue;
    }
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
