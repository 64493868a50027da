// The Quest 2 Touch importer (import_questset_csv, questset's CSV layout): the shipped trace imports whole
// and means what recordings/README.md says (7942 rows over 132.33 s; the left controller never moves; the
// grip pressed in a few frames, found here from the CSV text independently of the importer); TouchButtons
// is split between the hands; bad files are refused with the file, the line and the problem.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"  // TempDir: a fresh folder per test case
#include "csv_dialects.hpp"
#include "recording_checks.hpp"
#include "wedge/error.hpp"
#include "wedge/recordings/recording.hpp"

using namespace wedge::recordings;
using recording_checks::first_difference;
namespace fs = std::filesystem;

namespace {

const std::string kCsv = std::string(WEDGE_SOURCE_DIR) + "/recordings/quest2/sample_movement_data.csv";

const std::string kHeader =
    "TouchButtons,LeftIndexTrigger,RightIndexTrigger,LeftHandTrigger,RightHandTrigger,LeftTouchPosX,LeftTouchPosY,"
    "LeftTouchPosZ,LeftTouchOrientationW,LeftTouchOrientationX,LeftTouchOrientationY,LeftTouchOrientationZ,"
    "RightTouchPosX,RightTouchPosY,RightTouchPosZ,RightTouchOrientationW,RightTouchOrientationX,"
    "RightTouchOrientationY,RightTouchOrientationZ,HeadPosX,HeadPosY,HeadPosZ,HeadOrientationW,HeadOrientationX,"
    "HeadOrientationY,HeadOrientationZ,time";

// A row in kHeader's order: buttons, triggers (left index, right index, left hand, right hand), three poses
// with identity orientations, time.
std::string row(const std::string& buttons, const std::string& time, const std::string& right_hand = "0.5") {
  return buttons + ",0.1,0.2,0.3," + right_hand + ",1,2,3,1,0,0,0,4,5,6,0,1,0,0,7,8,9,0,0,0,1," + time;
}

std::vector<std::string> split(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> f;
  std::stringstream s(line);
  for (std::string x; std::getline(s, x, ',');) f.push_back(x);
  return f;
}

}  // namespace

TEST_CASE("Quest import: the shipped questset trace", "[recordings]") {
  const Recording r = import_questset_csv(kCsv);
  CHECK(r.source == "quest2-touch");
  CHECK(r.warnings.empty());
  REQUIRE(r.heads.size() == 7942);
  REQUIRE(r.hands.size() == 2 * 7942);
  CHECK(r.motion.empty());
  CHECK(r.heads.front().t == 0.0);
  CHECK(r.duration() == Approx(132.33).margin(0.01));
  CHECK(r.heads.back().t == Approx(132.349 - 0.0169733).epsilon(1e-12));

  // The CSV itself, read here: which rows have the grip pressed past half-way, and the left pose.
  std::ifstream in(kCsv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  const std::size_t grip = std::find(header.begin(), header.end(), "RightHandTrigger") - header.begin();
  const std::size_t left_x = std::find(header.begin(), header.end(), "LeftTouchPosX") - header.begin();
  REQUIRE(grip < header.size());
  REQUIRE(left_x < header.size());
  std::vector<bool> gripped;
  std::vector<double> left_x_values;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    gripped.push_back(std::strtod(f[grip].c_str(), nullptr) > 0.5);
    left_x_values.push_back(std::strtod(f[left_x].c_str(), nullptr));
  }
  REQUIRE(gripped.size() == 7942);
  const auto pressed = std::count(gripped.begin(), gripped.end(), true);
  CHECK(pressed > 0);  // "pressed in only a few frames"
  CHECK(pressed < 100);

  const Pose left0 = r.hands[0].pose;
  int mismatches = 0, moved = 0, disordered = 0;
  for (std::size_t i = 0; i < r.heads.size(); ++i) {
    const HandSample &left = r.hands[2 * i], &right = r.hands[2 * i + 1];
    if (left.hand != Hand::Left || right.hand != Hand::Right || left.t != r.heads[i].t || right.t != left.t)
      ++disordered;
    if ((right.squeeze > 0.5) != gripped[i]) ++mismatches;
    if (left.pose.position != left0.position || left.pose.orientation.coeffs() != left0.orientation.coeffs() ||
        left.pose.position.x() != left_x_values[i])
      ++moved;
    if (i > 0 && r.heads[i].t < r.heads[i - 1].t) ++disordered;
  }
  CHECK(disordered == 0);
  CHECK(mismatches == 0);
  CHECK(moved == 0);
  // The right controller does move: 0.6 to 0.86 m on each axis.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (std::size_t i = 1; i < r.hands.size(); i += 2) {
    lo = lo.cwiseMin(r.hands[i].pose.position);
    hi = hi.cwiseMax(r.hands[i].pose.position);
  }
  for (int k = 0; k < 3; ++k) CHECK((hi[k] - lo[k] > 0.55 && hi[k] - lo[k] < 0.9));
  for (const HandSample& h : r.hands) CHECK(std::abs(h.pose.orientation.norm() - 1.0) < 1e-12);

  // The shipped recording is this import, bit for bit.
  const Recording shipped = read_recording(std::string(WEDGE_SOURCE_DIR) + "/recordings/quest2/sample_movement.jsonl");
  CHECK(first_difference(r, shipped) == "");
}

// RFC 4180 as real tools write it: R's write.csv (quoted header names, a row-name column), a spreadsheet
// (byte-order mark, CRLF, no final newline), every field quoted with blank lines. Each imports to the
// plain file's recording, bit for bit.
TEST_CASE("Quest import: the dialects real tools write import to the same recording", "[recordings]") {
  const cli_runner::TempDir temp;
  const Recording plain = import_questset_csv(kCsv);
  std::ifstream in(kCsv, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::pair<const char*, std::string> dialects[] = {
      {"R write.csv", csv_dialects::r_write_csv(text)},
      {"spreadsheet", csv_dialects::spreadsheet(text)},
      {"quoted", csv_dialects::quoted_everywhere(text, false)},
  };
  for (const auto& [name, written] : dialects) {
    INFO(name);
    REQUIRE(written != text);
    const std::string path = (temp.path() / "dialect.csv").string();
    std::ofstream(path, std::ios::binary) << written;
    CHECK(first_difference(import_questset_csv(path), plain) == "");
  }
}

TEST_CASE("Quest import: columns in any order, CRLF, TouchButtons split between the hands", "[recordings]") {
  const cli_runner::TempDir temp;
  const fs::path& dir = temp.path();
  // The header with its first and last columns swapped, and the rows to match; CRLF line endings.
  std::string header = kHeader;
  header = "time" + header.substr(std::string("TouchButtons").size(), header.size() - 4 - 12) + "TouchButtons";
  auto swapped = [](const std::string& r) {
    const std::size_t first = r.find(','), last = r.rfind(',');
    return r.substr(last + 1) + r.substr(first, last - first + 1) + r.substr(0, first);
  };
  const std::string path = (dir / "order.csv").string();
  std::ofstream(path, std::ios::binary) << header << "\r\n"
                                        << swapped(row("769", "10.5")) << "\r\n"     // A | X | Y = 0x1 + 0x100 + 0x200
                                        << swapped(row("6", "10.75")) << "\r\n";     // B | 0x4 (not a kept bit)
  const Recording r = import_questset_csv(path);
  REQUIRE(r.hands.size() == 4);
  REQUIRE(r.heads.size() == 2);
  CHECK(r.hands[0].hand == Hand::Left);
  CHECK(r.hands[0].buttons == (kButtonX | kButtonY));
  CHECK(r.hands[1].buttons == kButtonA);
  CHECK(r.hands[2].buttons == 0);
  CHECK(r.hands[3].buttons == kButtonB);
  CHECK(r.hands[0].trigger == 0.1);
  CHECK(r.hands[1].trigger == 0.2);
  CHECK(r.hands[0].squeeze == 0.3);
  CHECK(r.hands[1].squeeze == 0.5);
  CHECK(r.hands[0].pose.position == Eigen::Vector3d(1, 2, 3));
  CHECK(r.hands[1].pose.position == Eigen::Vector3d(4, 5, 6));
  CHECK(r.hands[1].pose.orientation.coeffs() == Eigen::Vector4d(1, 0, 0, 0));  // W,X,Y,Z = 0,1,0,0; coeffs x,y,z,w
  CHECK(r.heads[0].pose.position == Eigen::Vector3d(7, 8, 9));
  CHECK(r.heads[0].pose.orientation.coeffs() == Eigen::Vector4d(0, 0, 1, 0));
  CHECK(r.heads[0].t == 0.0);
  CHECK(r.heads[1].t == 0.25);
  CHECK(r.hands[3].t == 0.25);
}

TEST_CASE("Quest import: bad files name the file, the line and the problem", "[recordings]") {
  const cli_runner::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string H = kHeader + "\n", a = row("0", "1") + "\n";
  struct Case {
    std::string text;
    int line;
    std::string problem;
  };
  const Case cases[] = {
      {"", 1, "empty file"},
      {"TouchButtons,time\n0,1\n", 1, "no column 'LeftIndexTrigger'"},
      {kHeader + ",Battery\n" + row("0", "1") + ",0.9\n", 1, "unknown column 'Battery'"},
      {kHeader + ",time\n" + row("0", "1") + ",1\n", 1, "column 'time' appears twice"},
      {H, 0, "no samples"},
      {H + a + row("0", "1").substr(2) + "\n", 3, "26 fields, the header has 27"},
      {H + a + row("0", "x") + "\n", 3, "time is not a finite number ('x')"},
      {H + row("0", "nan") + "\n", 2, "time is not a finite number ('nan')"},
      {H + row("0", "1", "") + "\n", 2, "RightHandTrigger is not a finite number ('')"},
      {H + row("0", "1", "1e999") + "\n", 2, "RightHandTrigger is not a finite number"},
      {H + row("0", "1", "1.5") + "\n", 2, "RightHandTrigger = 1.5 is outside [0, 1]"},
      {H + row("0.5", "1") + "\n", 2, "TouchButtons is not a button bit mask ('0.5')"},
      {H + row("-1", "1") + "\n", 2, "TouchButtons is not a button bit mask"},
      {H + a + row("0", "0.5") + "\n", 3, "time goes backwards (0.5 after 1)"},
      {H + a + "0,0.1,0.2,0.3,0.5,1,2,3,1,0,0,0.1,4,5,6,0,1,0,0,7,8,9,0,0,0,1,2\n", 3,
       "LeftTouchOrientation{W,X,Y,Z} is not a unit quaternion"},
      {H + a + "0,0.1,0.2,0.3,0.5,1,2,3,1,0,0,0,4,5,6,0,1,0,0,7,8,9,0,0,0,0,2\n", 3,
       "HeadOrientation{W,X,Y,Z} is not a unit quaternion (norm 0"},
      {H + a + "\"0" + row("0", "2").substr(1) + "\n", 3, "a quoted field is still open at the end of the file"},
      {H + a + "\"0\"1" + row("0", "2").substr(1) + "\n", 3, "malformed CSV quoting"},
      // A quoted field may hold a line break and any byte: the message quotes it on one line, escaped and
      // cut at 40 characters (a fuzzing finding: the refusal ran over several lines).
      {H + a + "\"1\n2\t\x01\"" + row("0", "2").substr(1) + "\n", 3, "TouchButtons is not a finite number ('1\\n2\\t\\x01')"},
      {H + a + "\"" + std::string(50, '7') + "x\"" + row("0", "2").substr(1) + "\n", 3,
       "('" + std::string(40, '7') + "...')"},
  };
  for (const Case& c : cases) {
    const std::string path = (dir / "bad.csv").string();
    std::ofstream(path, std::ios::binary) << c.text;
    INFO(c.text);
    try {
      import_questset_csv(path);
      FAIL("no error");
    } catch (const wedge::Error& e) {
      const std::string what = e.what();
      CHECK(what.rfind(c.line > 0 ? path + ":" + std::to_string(c.line) + ": " : path + ": ", 0) == 0);
      CHECK(what.find(c.problem) != std::string::npos);
      CHECK(what.find('\n') == std::string::npos);  // one line
    }
  }
  CHECK_THROWS_WITH(import_questset_csv((dir / "missing.csv").string()), Catch::Contains("missing.csv: cannot open"));
}
