// The recording format (recordings/recording.hpp, docs/recording-format.md): what is written reads back
// bit for bit (doubles of every kind, all three streams, merged by time); every malformed line is refused
// with the file, its line and the problem; a torn last line is dropped with a warning and nothing before
// it is lost; the writer is all or nothing. And the CoreMotion importer: raw acceleration =
// userAcceleration + gravity, checked against the CSV text read here independently of read_coremotion_csv.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "recording_checks.hpp"
#include "wedge/error.hpp"
#include "wedge/recordings/recording.hpp"

using namespace wedge::recordings;
using recording_checks::first_difference;
using recording_checks::same_bits;
namespace fs = std::filesystem;

namespace {

// A fresh folder per test case.
struct Folder {
  fs::path path;
  Folder() {
    std::string templ = (fs::temp_directory_path() / "wedge_recording_test_XXXXXX").string();
    REQUIRE(::mkdtemp(templ.data()) != nullptr);
    path = templ;
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
    return (path / name).string();
  }
};

const std::string kHeader =
    R"({"format":"wedge-recording","version":1,"source":"script","units":{"time":"s","position":"m",)"
    R"("acceleration":"g","rotation_rate":"rad/s"},"conventions":{"tracking":"OpenXR"}})";

std::string hand_line(const std::string& t, const std::string& extra = "") {
  return R"({"t":)" + t + R"(,"type":"hand","hand":"right","position":[0.1,1.2,-0.3],"orientation":[1,0,0,0],)"
         R"("squeeze":0.25,"trigger":1,"buttons":["A","Y"],"mode4d":true)" + extra + "}";
}
std::string head_line(const std::string& t) {
  return R"({"t":)" + t + R"(,"type":"head","position":[0,1.6,0],"orientation":[0.5,0.5,0.5,0.5]})";
}
std::string motion_line(const std::string& t) {
  return R"({"t":)" + t + R"(,"type":"motion","acceleration":[0,-1,0],"rotation_rate":[0.1,0.2,0.3],"tilt":false})";
}

// Replaces the first `from` in `s` by `to` (the case must change something).
std::string edit(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

double tricky(std::mt19937_64& rng, int i) {  // doubles whose shortest text is long, odd or extreme
  const double special[] = {0.1, 1.0 / 3.0, -0.0, 5e-324, 2.2250738585072014e-308, 1e300, -123456789.123456789,
                            std::nextafter(1.0, 2.0)};
  if (i % 3 == 0) return special[(i / 3) % 8];
  return std::uniform_real_distribution<double>(-10.0, 10.0)(rng);
}

}  // namespace

TEST_CASE("recording: write then read gives back every sample bit for bit", "[recordings]") {
  Folder dir;
  std::mt19937_64 rng(20240613);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Recording r;
  r.source = "script \"quoted\" \u00e9";
  double t = 0.0;
  int n = 0;
  auto vec3 = [&] {  // one at a time: the order of arguments' evaluation is unspecified
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = tricky(rng, n++);
    return v;
  };
  for (int i = 0; i < 300; ++i) {
    if (i % 4 != 0) t += unit(rng) * 0.02;  // repeated times too: merged order must not matter
    Pose pose;
    pose.position = vec3();
    for (int k = 0; k < 4; ++k) pose.orientation.coeffs()[k] = unit(rng) - 0.5;
    pose.orientation.normalize();
    if (i % 3 == 0) {
      HandSample h;
      h.t = t;
      h.hand = i % 2 ? Hand::Left : Hand::Right;
      h.pose = pose;
      h.squeeze = i % 5 == 0 ? 1.0 : unit(rng);
      h.trigger = i % 7 == 0 ? 0.0 : unit(rng) / 3.0;
      h.buttons = std::uint32_t(i) & (kButtonA | kButtonB | kButtonX | kButtonY);
      h.mode4d = i % 2 == 0;
      r.hands.push_back(h);
    } else if (i % 3 == 1) {
      r.heads.push_back({t, pose});
    } else {
      MotionSample m;
      m.t = t;
      m.acceleration = pose.position;
      m.has_rotation_rate = i % 4 != 0;
      if (m.has_rotation_rate) m.rotation_rate = vec3();
      m.tilt = i % 5 == 0;
      r.motion.push_back(m);
    }
  }
  r.hands.front().t = 0.0;
  const std::string path = (dir.path / "all.jsonl").string();
  write_recording(path, r);
  const Recording back = read_recording(path);
  CHECK(first_difference(r, back) == "");
  CHECK(back.warnings.empty());
  CHECK(same_bits(back.duration(), t));
  // Written again, the file is the same text.
  write_recording((dir.path / "again.jsonl").string(), back);
  std::ifstream a(path), b(dir.path / "again.jsonl");
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  CHECK(sa.str() == sb.str());
  // Nothing else in the folder: the temporary files were renamed into place.
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);
}

TEST_CASE("recording: a header-only file is an empty recording, CRLF lines and integers are fine", "[recordings]") {
  Folder dir;
  const Recording empty = read_recording(dir.write("empty.jsonl", kHeader + "\n"));
  CHECK(empty.source == "script");
  CHECK(empty.hands.empty());
  CHECK(empty.heads.empty());
  CHECK(empty.motion.empty());
  CHECK(empty.warnings.empty());
  CHECK(empty.duration() == 0.0);

  const Recording r = read_recording(dir.write("crlf.jsonl", kHeader + "\r\n" + hand_line("0") + "\r\n" +
                                                                 head_line("0.5") + "\r\n" + motion_line("2")));
  REQUIRE(r.hands.size() == 1);
  REQUIRE(r.heads.size() == 1);
  REQUIRE(r.motion.size() == 1);
  CHECK(r.warnings.empty());  // an unterminated last line that parses is a sample like any other
  const HandSample& h = r.hands[0];
  CHECK(h.hand == Hand::Right);
  CHECK(h.pose.position == Eigen::Vector3d(0.1, 1.2, -0.3));
  CHECK(h.squeeze == 0.25);
  CHECK(h.trigger == 1.0);
  CHECK(h.buttons == (kButtonA | kButtonY));
  CHECK(h.mode4d);
  CHECK(r.heads[0].pose.orientation.coeffs() == Eigen::Vector4d(0.5, 0.5, 0.5, 0.5));  // (x, y, z, w)
  CHECK(r.motion[0].has_rotation_rate);
  CHECK(r.motion[0].rotation_rate == Eigen::Vector3d(0.1, 0.2, 0.3));
  CHECK(r.duration() == 2.0);

  // A quaternion within 1e-3 of unit norm is normalised; rotation_rate may be left out.
  const Recording n = read_recording(dir.write(
      "near.jsonl", kHeader + "\n" + edit(head_line("0"), "[0.5,0.5,0.5,0.5]", "[1.0005,0,0,0]") + "\n" +
                        R"({"t":0,"type":"motion","acceleration":[0,-1,0],"tilt":true})" + "\n"));
  CHECK(n.heads[0].pose.orientation.coeffs() == Eigen::Vector4d(0, 0, 0, 1));
  CHECK_FALSE(n.motion[0].has_rotation_rate);
  CHECK(n.motion[0].rotation_rate == Eigen::Vector3d::Zero());
  CHECK(n.motion[0].tilt);
}

TEST_CASE("recording: a torn last line is dropped with a warning, everything before it kept", "[recordings]") {
  Folder dir;
  const std::string body =
      kHeader + "\n" + hand_line("0") + "\n" + head_line("0.01") + "\n" + motion_line("0.02") + "\n";
  const std::string path = dir.write("torn.jsonl", body + R"({"t":0.03,"type":"hand","hand":"ri)");
  const Recording r = read_recording(path);
  CHECK(r.hands.size() == 1);
  CHECK(r.heads.size() == 1);
  CHECK(r.motion.size() == 1);
  CHECK(r.duration() == 0.02);
  REQUIRE(r.warnings.size() == 1);
  CHECK(r.warnings[0] == path + ":5: torn last line (cut off mid-write), ignored");

  // The same fragment with its newline is no torn write but a broken line: an error.
  const std::string broken = dir.write("broken.jsonl", body + R"({"t":0.03,"type":"hand","hand":"ri)" + "\n");
  CHECK_THROWS_WITH(read_recording(broken), Catch::StartsWith(broken + ":5: not JSON"));
  // A torn header leaves no recording at all.
  const std::string header = dir.write("header.jsonl", kHeader.substr(0, 40));
  CHECK_THROWS_WITH(read_recording(header), Catch::StartsWith(header + ":1: not JSON"));
}

TEST_CASE("recording: malformed files name the file, the line and the problem", "[recordings]") {
  Folder dir;
  const std::string H = kHeader + "\n", a = hand_line("0") + "\n", b = head_line("0.5") + "\n";
  struct Case {
    std::string text;
    int line;
    std::string problem;
  };
  const Case cases[] = {
      // The header.
      {"", 1, "empty file"},
      {"\n" + a, 1, "empty line"},
      {"hello\n", 1, "not JSON"},
      {"[1,2]\n", 1, "unknown format"},
      {R"({"format":"other","version":1})" "\n", 1, R"(unknown format "other")"},
      {edit(H, R"("version":1)", R"("version":2)"), 1, "unsupported version 2 (this build reads 1)"},
      {edit(H, R"("version":1)", R"("version":"1")"), 1, "'version' must be an integer"},
      {edit(H, R"("version":1,)", ""), 1, "missing key 'version'"},
      {edit(H, R"("source":"script")", R"("source":3)"), 1, "'source' must be a string"},
      {edit(H, R"("source":"script",)", ""), 1, "missing key 'source'"},
      {edit(H, R"("source")", R"("extra":0,"source")"), 1, "unknown key 'extra'"},
      {edit(H, R"("time":"s")", R"("time":"ms")"), 1, R"(units: 'time' must be "s", got "ms")"},
      {edit(H, R"("position":"m",)", ""), 1, "units: missing key 'position'"},
      {edit(H, R"("time":"s")", R"("time":"s","angle":"rad")"), 1, "units: unknown key 'angle'"},
      {edit(H, R"({"tracking":"OpenXR"})", "3"), 1, "'conventions' must be an object"},
      // Whole lines.
      {H + "\n" + a, 2, "empty line"},
      {H + "[0]\n", 2, "expected a sample"},
      {H + R"({"t":NaN,"type":"head"})" "\n" + b, 2, "not JSON"},
      {H + a + "{\"t\":\n" + b, 3, "not JSON"},
      {H + edit(a, "[0.1,", "[1e999,"), 2, "a number is not finite"},
      {H + edit(a, R"("mode4d":true)", R"("mode4d":true,"t":1)"), 2, "duplicate key 't'"},
      // Keys and types.
      {H + edit(a, R"(,"type":"hand")", ""), 2, "missing key 'type'"},
      {H + edit(a, R"("type":"hand")", R"("type":"foot")"), 2, "unknown sample type 'foot'"},
      {H + edit(a, R"("squeeze":0.25,)", ""), 2, "missing key 'squeeze'"},
      {H + edit(a, R"("squeeze")", R"("squeez")"), 2, "unknown key 'squeez'"},
      {H + a + edit(b, R"("position")", R"("squeeze":0,"position")"), 3, "unknown key 'squeeze'"},
      {H + edit(a, R"("t":0)", R"("t":"0")"), 2, "'t' must be a number, got string"},
      {H + edit(a, R"("hand":"right")", R"("hand":"middle")"), 2, R"('hand' must be "left" or "right")"},
      {H + edit(a, "[0.1,1.2,-0.3]", "[0.1,1.2]"), 2, "'position' must be an array of 3 numbers, got an array of 2"},
      {H + edit(a, "[0.1,1.2,-0.3]", "\"here\""), 2, "'position' must be an array of 3 numbers, got a string"},
      {H + edit(a, "[0.1,1.2,-0.3]", "[0.1,null,-0.3]"), 2, "'position[1]' must be a number, got null"},
      {H + edit(a, "[1,0,0,0]", "[1,0,0]"), 2, "'orientation' must be an array of 4 numbers"},
      {H + edit(a, "[1,0,0,0]", "[1,0,0,0.1]"), 2, "'orientation' is not a unit quaternion"},
      {H + edit(a, "[1,0,0,0]", "[1.002,0,0,0]"), 2, "'orientation' is not a unit quaternion (norm 1.002"},
      {H + edit(a, R"("squeeze":0.25)", R"("squeeze":1.5)"), 2, "'squeeze' = 1.5 is outside [0, 1]"},
      {H + edit(a, R"("trigger":1)", R"("trigger":-0.1)"), 2, "'trigger' = -0.1 is outside [0, 1]"},
      {H + edit(a, R"("trigger":1)", R"("trigger":true)"), 2, "'trigger' must be a number, got boolean"},
      {H + edit(a, R"(["A","Y"])", R"(["A","Z"])"), 2, R"(unknown button "Z")"},
      {H + edit(a, R"(["A","Y"])", R"("A")"), 2, "'buttons' must be an array"},
      {H + edit(a, R"("mode4d":true)", R"("mode4d":1)"), 2, "'mode4d' must be true or false"},
      {H + edit(motion_line("0"), "[0,-1,0]", "[0,-1,0,0]") + "\n", 2, "'acceleration' must be an array of 3"},
      {H + edit(motion_line("0"), R"(,"tilt":false)", "") + "\n", 2, "missing key 'tilt'"},
      // Time.
      {H + edit(a, R"("t":0)", R"("t":-1)"), 2, "'t' = -1 is negative"},
      {H + hand_line("1") + "\n" + hand_line("0.5") + "\n", 3, "time goes backwards: t = 0.5 after 1"},
      {H + a + b + motion_line("0.25") + "\n", 4, "time goes backwards: t = 0.25 after 0.5"},
      // A malformed last line that is no torn write: it parses, or it ends in a newline.
      {H + a + edit(b, R"("position")", R"("extra":1,"position")").substr(0, b.size() + 9), 3, "unknown key 'extra'"},
      {H + a + "garbage\n", 3, "not JSON"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("bad.jsonl", c.text);
    INFO(c.text);
    try {
      read_recording(path);
      FAIL("no error");
    } catch (const wedge::Error& e) {
      const std::string what = e.what();
      CHECK(what.rfind(path + ":" + std::to_string(c.line) + ": ", 0) == 0);
      CHECK(what.find(c.problem) != std::string::npos);
      CHECK(what.find('\n') == std::string::npos);
    }
  }
  CHECK_THROWS_WITH(read_recording((dir.path / "missing.jsonl").string()),
                    Catch::Contains("missing.jsonl: cannot open file"));
}

TEST_CASE("recording: the writer is all or nothing and writes only what reads back", "[recordings]") {
  Folder dir;
  Recording r;
  r.source = "script";
  r.hands.resize(2);
  r.hands[0].t = 1.0;
  r.hands[1].t = 0.5;  // backwards
  const std::string path = (dir.path / "out.jsonl").string();
  CHECK_THROWS_WITH(write_recording(path, r),
                    Catch::StartsWith(path + ": cannot write hands[1]: time goes backwards: t = 0.5 after 1"));
  r.hands[1].t = 1.0;
  r.hands[1].squeeze = 2.0;
  CHECK_THROWS_WITH(write_recording(path, r), Catch::Contains("hands[1]: squeeze = 2 is outside [0, 1]"));
  r.hands[1].squeeze = 1.0;
  r.hands[1].pose.position.y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(write_recording(path, r), Catch::Contains("hands[1]: position is not finite"));
  CHECK(fs::is_empty(dir.path));  // no output file and no temporary left behind
  CHECK_THROWS_AS(write_recording((dir.path / "no" / "such" / "dir.jsonl").string(), Recording{}), wedge::Error);

  // An existing file is replaced whole.
  std::ofstream(path) << "old contents\n";
  write_recording(path, Recording{"viewer", {}, {}, {}, {}});
  CHECK(read_recording(path).source == "viewer");
}

TEST_CASE("CoreMotion import: acceleration = userAcceleration + gravity, time from 0", "[recordings]") {
  const std::string csv = std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor_data.csv";
  const Recording r = import_coremotion_csv(csv);
  CHECK(r.source == "coremotion");
  CHECK(r.hands.empty());
  CHECK(r.heads.empty());
  REQUIRE(r.motion.size() == 869);
  CHECK(r.duration() == Approx(9.356071250047535).epsilon(1e-12));

  // The CSV's first rows, read here from the text.
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  auto fields = [](std::string l) {
    if (!l.empty() && l.back() == '\r') l.pop_back();  // the trace has CRLF line endings
    std::vector<std::string> f;
    std::stringstream s(l);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    return f;
  };
  const std::vector<std::string> header = fields(line);
  auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    REQUIRE(it != header.end());
    return std::size_t(it - header.begin());
  };
  double t0 = 0.0;
  for (int row = 0; row < 20; ++row) {
    REQUIRE(std::getline(in, line));
    const std::vector<std::string> f = fields(line);
    auto v = [&](const std::string& name) { return std::strtod(f[col(name)].c_str(), nullptr); };
    if (row == 0) t0 = v("timestamp");
    const MotionSample& m = r.motion[row];
    CHECK(same_bits(m.t, v("timestamp") - t0));
    for (int k = 0; k < 3; ++k) {
      const std::string axis = std::string(1, "xyz"[k]);
      CHECK(same_bits(m.acceleration[k], v("userAcceleration." + axis) + v("gravity." + axis)));
      CHECK(same_bits(m.rotation_rate[k], v("rotationRate." + axis)));
    }
    CHECK(m.has_rotation_rate);
    CHECK_FALSE(m.tilt);
  }
  CHECK(r.motion.front().t == 0.0);
  // A phone held in the hand: the raw accelerometer is about 1 g.
  CHECK(r.motion.front().acceleration.norm() == Approx(1.0).margin(0.15));

  // The shipped recording is this import, bit for bit.
  const Recording shipped =
      read_recording(std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor.jsonl");
  CHECK(first_difference(r, shipped) == "");
  CHECK(shipped.warnings.empty());
}
