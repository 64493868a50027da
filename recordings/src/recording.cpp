// The recording format (docs/recording-format.md): reader, writer. Strict on purpose: a recording is test
// input, and a file that is only nearly right (a renamed key, a wrong unit) must fail loudly, at its line.
#include "wedge/recordings/recording.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "unit_quaternion.hpp"
#include "wedge/error.hpp"
#include "wedge/fp_env.hpp"
#include "wedge/ga/types.hpp"

namespace wedge::recordings {
namespace {

using Json = nlohmann::json;
using OutJson = nlohmann::ordered_json;  // the writer keeps "t" and "type" first

constexpr std::array<const char*, 4> kUnitKeys = {"time", "position", "acceleration", "rotation_rate"};
constexpr std::array<const char*, 4> kUnitValues = {"s", "m", "g", "rad/s"};
constexpr std::array<std::pair<std::uint32_t, const char*>, 4> kButtons = {
    {{kButtonA, "A"}, {kButtonB, "B"}, {kButtonX, "X"}, {kButtonY, "Y"}}};

// Shortest text that reads back to the same double (as the writer writes it, less a trailing ".0"), for messages.
std::string num(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::string text = Json(x).dump();
  if (text.size() > 2 && text.compare(text.size() - 2, 2, ".0") == 0) text.resize(text.size() - 2);
  return text;
}

// One line of the file being read: every problem is reported as "PATH:LINE: problem".
class LineReader {
 public:
  LineReader(const std::string& path, int line) : path_(path), line_(line) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(path_ + ":" + std::to_string(line_) + ": " + problem);
  }

  // Unknown keys first: a misspelt key is better named as itself than as the key it should have been.
  void only_keys(const Json& object, std::initializer_list<const char*> allowed, const std::string& where = "") const {
    for (const auto& item : object.items())
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* k) { return item.key() == k; }))
        fail(where + "unknown key '" + printable(item.key()) + "'");
  }
  const Json& need(const Json& object, const char* key, const std::string& where = "") const {
    const auto it = object.find(key);
    if (it == object.end()) fail(where + "missing key '" + key + "'");
    return *it;
  }
  double number(const Json& object, const char* key) const { return number_value(need(object, key), key); }
  double number_value(const Json& v, const std::string& key) const {
    if (!v.is_number()) fail("'" + key + "' must be a number, got " + v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail("'" + key + "' is not finite");
    return x;
  }
  double unit_interval(const Json& object, const char* key) const {
    const double x = number(object, key);
    if (!(x >= 0.0 && x <= 1.0)) fail("'" + std::string(key) + "' = " + num(x) + " is outside [0, 1]");
    return x;
  }
  bool boolean(const Json& object, const char* key) const {
    const Json& v = need(object, key);
    if (!v.is_boolean()) fail("'" + std::string(key) + "' must be true or false, got " + v.type_name());
    return v.get<bool>();
  }
  std::string string(const Json& object, const char* key) const {
    const Json& v = need(object, key);
    if (!v.is_string()) fail("'" + std::string(key) + "' must be a string, got " + v.type_name());
    return v.get<std::string>();
  }
  template <int Size>
  Eigen::Matrix<double, Size, 1> numbers(const Json& object, const char* key) const {
    const Json& v = need(object, key);
    if (!v.is_array() || v.size() != Size)
      fail("'" + std::string(key) + "' must be an array of " + std::to_string(Size) + " numbers, got " +
           (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string("a ") + v.type_name()));
    Eigen::Matrix<double, Size, 1> out;
    for (int i = 0; i < Size; ++i) out[i] = number_value(v[i], std::string(key) + "[" + std::to_string(i) + "]");
    return out;
  }
  Pose pose(const Json& object) const {
    Pose p;
    p.position = numbers<3>(object, "position");
    const Eigen::Vector4d wxyz = numbers<4>(object, "orientation");
    p.orientation = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    double norm = 0.0;
    if (!accept_unit_quaternion(p.orientation, norm))
      fail("'orientation' is not a unit quaternion (norm " + num(norm) + ", more than 1e-3 from 1)");
    return p;
  }

 private:
  const std::string& path_;
  int line_;
};

// Parses one line; a JSON syntax error is reported through `syntax_error` (the caller decides whether the
// line is torn), anything else fails at once. Duplicate keys are refused: nlohmann would keep the last.
bool parse_line(const LineReader& at, std::string_view text, Json& out, std::string& syntax_error) {
  std::vector<std::vector<std::string>> keys;  // of each open object
  std::string duplicate;
  auto watch = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) keys.emplace_back();
    if (event == Json::parse_event_t::object_end) keys.pop_back();
    if (event == Json::parse_event_t::key) {
      const std::string key = parsed.get<std::string>();
      if (std::find(keys.back().begin(), keys.back().end(), key) != keys.back().end()) {
        if (duplicate.empty()) duplicate = key;
      } else {
        keys.back().push_back(key);
      }
    }
    return true;
  };
  try {
    const ExpectedFpExceptions quiet;  // 1e999 overflows while parsed: reported below as out of range
    out = Json::parse(text.begin(), text.end(), watch);
  } catch (const Json::parse_error& e) {
    std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line 1, column 5: ..."
    for (const char* prefix : {"] ", "at line 1, "})
      if (const auto p = what.find(prefix); p != std::string::npos) what = what.substr(p + std::strlen(prefix));
    syntax_error = "not JSON (" + what + ")";
    return false;
  } catch (const Json::out_of_range& e) {  // 1e999: JSON that no double can hold
    std::string what = e.what();
    what = what.substr(what.find("] ") + 2);
    at.fail("a number is not finite (" + what + ")");
  }
  if (!duplicate.empty()) at.fail("duplicate key '" + printable(duplicate) + "'");
  return true;
}

void read_header(const LineReader& at, const Json& h, Recording& r) {
  if (!h.is_object() || !h.contains("format"))
    at.fail("unknown format (the first line is not a wedge-recording header: no \"format\" key)");
  const Json& format = h["format"];
  if (!format.is_string() || format.get<std::string>() != "wedge-recording")
    at.fail("unknown format " + format.dump() + " (expected \"wedge-recording\")");
  const Json& version = at.need(h, "version");
  if (!version.is_number_integer()) at.fail("'version' must be an integer, got " + version.dump());
  if (version.get<std::int64_t>() != kRecordingVersion)
    at.fail("unsupported version " + version.dump() + " (this build reads " + std::to_string(kRecordingVersion) +
            ")");
  at.only_keys(h, {"format", "version", "source", "units", "conventions"});
  r.source = at.string(h, "source");
  const Json& units = at.need(h, "units");
  if (!units.is_object()) at.fail("'units' must be an object, got " + std::string(units.type_name()));
  at.only_keys(units, {kUnitKeys[0], kUnitKeys[1], kUnitKeys[2], kUnitKeys[3]}, "units: ");
  for (std::size_t k = 0; k < kUnitKeys.size(); ++k) {
    const Json& unit = at.need(units, kUnitKeys[k], "units: ");
    if (!unit.is_string() || unit.get<std::string>() != kUnitValues[k])
      at.fail(std::string("units: '") + kUnitKeys[k] + "' must be \"" + kUnitValues[k] + "\", got " + unit.dump());
  }
  // Conventions are for the human reader; the units above are what the numbers depend on.
  const Json& conventions = at.need(h, "conventions");
  if (!conventions.is_object()) at.fail("'conventions' must be an object, got " + std::string(conventions.type_name()));
  for (const auto& item : conventions.items())
    if (!item.value().is_string()) at.fail("conventions: '" + printable(item.key()) + "' must be a string");
}

// One sample line into `r`; returns its time.
double read_sample(const LineReader& at, const Json& s, Recording& r) {
  if (!s.is_object()) at.fail("expected a sample (a JSON object), got " + std::string(s.type_name()));
  const std::string type = at.string(s, "type");
  if (type == "hand") {
    at.only_keys(s, {"t", "type", "hand", "position", "orientation", "squeeze", "trigger", "buttons", "mode4d"});
  } else if (type == "head") {
    at.only_keys(s, {"t", "type", "position", "orientation"});
  } else if (type == "motion") {
    at.only_keys(s, {"t", "type", "acceleration", "rotation_rate", "tilt"});
  } else {
    at.fail("unknown sample type '" + printable(type) + "' (expected hand, head or motion)");
  }
  const double t = at.number(s, "t");
  if (t < 0.0) at.fail("'t' = " + num(t) + " is negative");
  if (type == "hand") {
    HandSample h;
    h.t = t;
    const std::string hand = at.string(s, "hand");
    if (hand != "left" && hand != "right") at.fail("'hand' must be \"left\" or \"right\", got \"" + hand + "\"");
    h.hand = hand == "left" ? Hand::Left : Hand::Right;
    h.pose = at.pose(s);
    h.squeeze = at.unit_interval(s, "squeeze");
    h.trigger = at.unit_interval(s, "trigger");
    const Json& buttons = at.need(s, "buttons");
    if (!buttons.is_array())
      at.fail("'buttons' must be an array of button names, got " + std::string(buttons.type_name()));
    for (const Json& b : buttons) {
      const auto it = std::find_if(kButtons.begin(), kButtons.end(),
                                   [&](const auto& kb) { return b.is_string() && b.get<std::string>() == kb.second; });
      if (it == kButtons.end()) at.fail("unknown button " + b.dump() + " (the buttons are \"A\", \"B\", \"X\", \"Y\")");
      h.buttons |= it->first;
    }
    h.mode4d = at.boolean(s, "mode4d");
    r.hands.push_back(h);
  } else if (type == "head") {
    r.heads.push_back({t, at.pose(s)});
  } else {
    MotionSample m;
    m.t = t;
    m.acceleration = at.numbers<3>(s, "acceleration");
    m.has_rotation_rate = s.contains("rotation_rate");
    if (m.has_rotation_rate) m.rotation_rate = at.numbers<3>(s, "rotation_rate");
    m.tilt = at.boolean(s, "tilt");
    r.motion.push_back(m);
  }
  return t;
}

OutJson to_json(const Eigen::Vector3d& v) { return OutJson::array({v.x(), v.y(), v.z()}); }
OutJson to_json(const Eigen::Quaterniond& q) { return OutJson::array({q.w(), q.x(), q.y(), q.z()}); }

// The writer refuses what the reader would: a file it writes always reads back.
class SampleWriter {
 public:
  explicit SampleWriter(const std::string& path) : path_(path) {}

  void time(double t, const std::string& where) {
    if (!std::isfinite(t) || t < 0.0) fail(where, "t = " + num(t) + " is not a finite time >= 0");
    if (t < last_t_) fail(where, "time goes backwards: t = " + num(t) + " after " + num(last_t_));
    last_t_ = t;
  }
  void finite(const Eigen::Vector3d& v, const std::string& where, const char* key) const {
    if (!all_finite(v)) fail(where, std::string(key) + " is not finite");
  }
  void pose(const Pose& p, const std::string& where) const {
    finite(p.position, where, "position");
    const double norm = p.orientation.norm();
    if (!(std::abs(norm - 1.0) <= kUnitQuaternionTolerance))
      fail(where, "orientation is not a unit quaternion (norm " + num(norm) + ")");
  }
  void unit_interval(double x, const std::string& where, const char* key) const {
    if (!(x >= 0.0 && x <= 1.0)) fail(where, std::string(key) + " = " + num(x) + " is outside [0, 1]");
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw Error(path_ + ": cannot write " + where + ": " + problem);
  }
  std::string path_;
  double last_t_ = 0.0;
};

std::string header_line(const std::string& source) {
  OutJson h;
  h["format"] = "wedge-recording";
  h["version"] = kRecordingVersion;
  h["source"] = source;
  OutJson units;
  for (std::size_t k = 0; k < kUnitKeys.size(); ++k) units[kUnitKeys[k]] = kUnitValues[k];
  h["units"] = units;
  h["conventions"] = {
      {"tracking", "x right, y up, z toward the user (OpenXR)"},
      {"orientation", "unit quaternion [w, x, y, z], local -> tracking"},
      {"device", "x right, y up, z out of the screen"},
      {"acceleration", "gravity included, pointing the way it pulls (still upright phone: [0, -1, 0])"},
      {"buttons", "Oculus Touch: A, B on the right hand, X, Y on the left"},
  };
  return h.dump();
}

// One sample as its line (no newline), checked as the reader would check it.
std::string sample_line(SampleWriter& check, const HandSample& h, const std::string& where) {
  check.time(h.t, where);
  check.pose(h.pose, where);
  check.unit_interval(h.squeeze, where, "squeeze");
  check.unit_interval(h.trigger, where, "trigger");
  OutJson s;
  s["t"] = h.t;
  s["type"] = "hand";
  s["hand"] = h.hand == Hand::Left ? "left" : "right";
  s["position"] = to_json(h.pose.position);
  s["orientation"] = to_json(h.pose.orientation);
  s["squeeze"] = h.squeeze;
  s["trigger"] = h.trigger;
  s["buttons"] = OutJson::array();
  for (const auto& [bit, name] : kButtons)
    if (h.buttons & bit) s["buttons"].push_back(name);
  s["mode4d"] = h.mode4d;
  return s.dump();
}
std::string sample_line(SampleWriter& check, const HeadSample& g, const std::string& where) {
  check.time(g.t, where);
  check.pose(g.pose, where);
  OutJson s;
  s["t"] = g.t;
  s["type"] = "head";
  s["position"] = to_json(g.pose.position);
  s["orientation"] = to_json(g.pose.orientation);
  return s.dump();
}
std::string sample_line(SampleWriter& check, const MotionSample& m, const std::string& where) {
  check.time(m.t, where);
  check.finite(m.acceleration, where, "acceleration");
  OutJson s;
  s["t"] = m.t;
  s["type"] = "motion";
  s["acceleration"] = to_json(m.acceleration);
  if (m.has_rotation_rate) {
    check.finite(m.rotation_rate, where, "rotation_rate");
    s["rotation_rate"] = to_json(m.rotation_rate);
  }
  s["tilt"] = m.tilt;
  return s.dump();
}

// The whole file, or nothing: a temporary file beside it, synced, then renamed into place.
void write_atomically(const std::string& path, const std::string& text) {
  std::string temp = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) throw Error(path + ": cannot create output file (" + std::strerror(errno) + ")");
  const mode_t mask = ::umask(0);  // mkstemp makes the file 0600; give it what a plain fopen would
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  const int err = errno;
  const bool ok = done == text.size() && ::fsync(fd) == 0;
  const int sync_err = errno;
  if (::close(fd) != 0 || !ok) {
    std::remove(temp.c_str());
    throw Error(path + ": write failed (" + std::strerror(done == text.size() ? sync_err : err) + ")");
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const int rename_err = errno;
    std::remove(temp.c_str());
    throw Error(path + ": cannot rename the output into place (" + std::strerror(rename_err) + ")");
  }
}

}  // namespace

double Recording::duration() const {
  double d = 0.0;
  if (!hands.empty()) d = std::max(d, hands.back().t);
  if (!heads.empty()) d = std::max(d, heads.back().t);
  if (!motion.empty()) d = std::max(d, motion.back().t);
  return d;
}

Recording read_recording(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (in.bad()) throw Error(path + ": read failed");
  if (text.empty()) throw Error(path + ":1: empty file (expected a wedge-recording header line)");

  Recording r;
  double last_t = 0.0;
  int number = 1;
  for (std::size_t begin = 0; begin < text.size(); ++number) {
    const std::size_t newline = text.find('\n', begin);
    const bool terminated = newline != std::string::npos;
    const std::size_t end = terminated ? newline : text.size();
    std::string_view line(text.data() + begin, end - begin);
    begin = terminated ? newline + 1 : text.size();
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF from an editor is still the line

    const LineReader at(path, number);
    if (line.empty()) at.fail(number == 1 ? "empty line (expected a wedge-recording header)" : "empty line");
    Json j;
    std::string syntax_error;
    if (!parse_line(at, line, j, syntax_error)) {
      // A writer killed mid-line leaves an unterminated fragment at the end: drop it, keep the rest.
      if (!terminated && number > 1) {
        r.warnings.push_back(path + ":" + std::to_string(number) + ": torn last line (cut off mid-write), ignored");
        break;
      }
      at.fail(syntax_error);
    }
    if (number == 1) {
      read_header(at, j, r);
      continue;
    }
    const double t = read_sample(at, j, r);
    if (t < last_t) at.fail("time goes backwards: t = " + num(t) + " after " + num(last_t));
    last_t = t;
  }
  return r;
}

void write_recording(const std::string& path, const Recording& r) {
  std::string text = header_line(r.source) + "\n";
  SampleWriter check(path);
  std::size_t i = 0, j = 0, k = 0;  // next hand, head and motion sample: merged by time
  const double inf = std::numeric_limits<double>::infinity();
  while (i < r.hands.size() || j < r.heads.size() || k < r.motion.size()) {
    const double th = i < r.hands.size() ? r.hands[i].t : inf;
    const double tg = j < r.heads.size() ? r.heads[j].t : inf;
    const double tm = k < r.motion.size() ? r.motion[k].t : inf;
    if (i < r.hands.size() && !(tg < th) && !(tm < th))  // ties: hands, then heads, then motion
      text += sample_line(check, r.hands[i], "hands[" + std::to_string(i) + "]"), ++i;
    else if (j < r.heads.size() && !(tm < tg))
      text += sample_line(check, r.heads[j], "heads[" + std::to_string(j) + "]"), ++j;
    else
      text += sample_line(check, r.motion[k], "motion[" + std::to_string(k) + "]"), ++k;
    text += '\n';
  }
  write_atomically(path, text);
}

// The streaming writer: the same lines as write_recording, each written with one write(2) and flushed.
struct RecordingWriter::Impl {
  std::string path;
  int fd = -1;
  SampleWriter check;
  std::int64_t samples = 0;
  explicit Impl(const std::string& p) : path(p), check(path) {}
  void line(const std::string& text) {
    const std::string out = text + "\n";
    std::size_t done = 0;
    while (done < out.size()) {
      const ssize_t n = ::write(fd, out.data() + done, out.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw Error(path + ": write failed (" + std::strerror(errno) + ")");
      done += std::size_t(n);
    }
  }
};

RecordingWriter::RecordingWriter(const std::string& path, const std::string& source) : impl_(new Impl(path)) {
  impl_->fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (impl_->fd < 0) throw Error(path + ": cannot create the recording (" + std::strerror(errno) + ")");
  impl_->line(header_line(source));
}

RecordingWriter::~RecordingWriter() {
  if (impl_->fd >= 0) ::close(impl_->fd);
}

void RecordingWriter::write(const HandSample& s) {
  impl_->line(sample_line(impl_->check, s, "hand sample " + std::to_string(impl_->samples + 1)));
  ++impl_->samples;
}
void RecordingWriter::write(const HeadSample& s) {
  impl_->line(sample_line(impl_->check, s, "head sample " + std::to_string(impl_->samples + 1)));
  ++impl_->samples;
}
void RecordingWriter::write(const MotionSample& s) {
  impl_->line(sample_line(impl_->check, s, "motion sample " + std::to_string(impl_->samples + 1)));
  ++impl_->samples;
}

void RecordingWriter::write_frame(const input::InputFrame& frame) {
  for (const MotionSample& m : frame.motion) write(m);
  for (int k = 0; k < input::kHandCount; ++k) {
    const input::HandInput& in = frame.hands[std::size_t(k)];
    if (!in.tracked) continue;
    HandSample s;
    s.t = frame.t;
    s.hand = Hand(k);
    s.pose.position = in.position;
    s.pose.orientation = in.orientation;
    s.squeeze = in.squeeze;
    s.trigger = in.trigger;
    s.buttons = in.buttons;
    s.mode4d = in.mode4d;
    write(s);
  }
}

std::int64_t RecordingWriter::samples() const { return impl_->samples; }

void RecordingWriter::close() {
  if (impl_->fd < 0) return;
  const bool synced = ::fsync(impl_->fd) == 0;
  const int err = errno;
  const bool closed = ::close(impl_->fd) == 0;
  impl_->fd = -1;
  if (!synced || !closed) throw Error(impl_->path + ": write failed (" + std::strerror(closed ? err : errno) + ")");
}

}  // namespace wedge::recordings
