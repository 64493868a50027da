// Importers: other devices' recordings into the recording format (recording.hpp). Values are kept as
// recorded; only the clock is rebased to start at 0 and near-unit quaternions are normalised.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "csv_table.hpp"
#include "wedge/parse_number.hpp"
#include "unit_quaternion.hpp"
#include "wedge/error.hpp"
#include "wedge/recordings/coremotion_csv.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::recordings {
namespace {

// The questset columns (signetlabdei/questset, Oculus PC SDK names), in the order read below.
constexpr std::array<const char*, 27> kQuestColumns = {
    "TouchButtons",          "LeftIndexTrigger",      "RightIndexTrigger",     "LeftHandTrigger",
    "RightHandTrigger",      "LeftTouchPosX",         "LeftTouchPosY",         "LeftTouchPosZ",
    "LeftTouchOrientationW", "LeftTouchOrientationX", "LeftTouchOrientationY", "LeftTouchOrientationZ",
    "RightTouchPosX",        "RightTouchPosY",        "RightTouchPosZ",        "RightTouchOrientationW",
    "RightTouchOrientationX", "RightTouchOrientationY", "RightTouchOrientationZ", "HeadPosX",
    "HeadPosY",              "HeadPosZ",              "HeadOrientationW",      "HeadOrientationX",
    "HeadOrientationY",      "HeadOrientationZ",      "time"};
enum QuestColumn { kButtons, kLeftIndex, kRightIndex, kLeftHand, kRightHand, kLeftPose = 5, kRightPose = 12,
                   kHeadPose = 19, kTime = 26 };

}  // namespace

Recording import_questset_csv(const std::string& path) {
  const std::vector<CsvRecord> records = read_csv(path);
  auto fail = [&](int line, const std::string& problem) {
    throw Error(path + ":" + std::to_string(line) + ": " + problem);
  };
  if (records.empty()) fail(1, "empty file (expected a header row naming the questset columns)");
  const std::vector<std::string>& header = records.front().fields;
  const int header_line = records.front().line;
  std::array<std::size_t, kQuestColumns.size()> column{};
  for (std::size_t k = 0; k < kQuestColumns.size(); ++k) {
    std::size_t c = 0;
    while (c < header.size() && header[c] != kQuestColumns[k]) ++c;
    if (c == header.size()) fail(header_line, std::string("no column '") + kQuestColumns[k] + "' in the header");
    column[k] = c;
  }
  // Every column must be one of the 27, once: an unknown one may be a renamed column whose data would be lost.
  // A column with an empty name is a row index (R's write.csv row names, pandas' to_csv index): not data.
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c].empty()) continue;
    const std::size_t k = std::find(kQuestColumns.begin(), kQuestColumns.end(), header[c]) - kQuestColumns.begin();
    if (k == kQuestColumns.size())
      fail(header_line, "unknown column '" + printable(header[c]) + "' (questset has 27 known columns)");
    if (column[k] != c) fail(header_line, "column '" + printable(header[c]) + "' appears twice");
  }

  Recording r;
  r.source = "quest2-touch";
  double t0 = 0.0, last_time = 0.0;
  std::string last_time_text;
  for (std::size_t record = 1; record < records.size(); ++record) {
    const int number = records[record].line;
    const std::vector<std::string>& fields = records[record].fields;
    if (fields.size() != header.size())
      fail(number, std::to_string(fields.size()) + " fields, the header has " + std::to_string(header.size()));
    std::array<double, kQuestColumns.size()> v{};
    for (std::size_t k = 0; k < kQuestColumns.size(); ++k) {
      const std::string& text = fields[column[k]];
      if (!parse_finite(text, v[k]))
        fail(number, std::string(kQuestColumns[k]) + " is not a finite number ('" + printable(text) + "')");
    }
    if (v[kButtons] < 0 || v[kButtons] > 4294967295.0 || v[kButtons] != std::floor(v[kButtons]))
      fail(number, "TouchButtons is not a button bit mask ('" + printable(fields[column[kButtons]]) + "')");
    for (const int k : {kLeftIndex, kRightIndex, kLeftHand, kRightHand})
      if (!(v[k] >= 0.0 && v[k] <= 1.0))
        fail(number, std::string(kQuestColumns[k]) + " = " + printable(fields[column[k]]) + " is outside [0, 1]");
    if (r.heads.empty()) {
      t0 = v[kTime];
    } else if (v[kTime] < last_time) {
      fail(number, "time goes backwards (" + printable(fields[column[kTime]]) + " after " + printable(last_time_text) + ")");
    }
    last_time = v[kTime];
    last_time_text = fields[column[kTime]];
    const double t = v[kTime] - t0;  // rounding is monotone: a non-decreasing clock stays non-decreasing

    auto pose = [&](int first, const char* name) {
      Pose p;
      p.position = {v[first], v[first + 1], v[first + 2]};
      p.orientation = Eigen::Quaterniond(v[first + 3], v[first + 4], v[first + 5], v[first + 6]);
      double norm = 0.0;
      if (!accept_unit_quaternion(p.orientation, norm))
        fail(number, std::string(name) + "Orientation{W,X,Y,Z} is not a unit quaternion (norm " +
                         std::to_string(norm) + ", more than 1e-3 from 1)");
      return p;
    };
    // TouchButtons is one mask for both controllers: A and B are on the right one, X and Y on the left.
    const auto buttons = std::uint32_t(v[kButtons]);
    auto hand = [&](Hand which, int first, const char* name, int squeeze, int trigger, std::uint32_t mask) {
      HandSample h;
      h.t = t;
      h.hand = which;
      h.pose = pose(first, name);
      h.squeeze = v[squeeze];
      h.trigger = v[trigger];
      h.buttons = buttons & mask;
      return h;
    };
    const HandSample left = hand(Hand::Left, kLeftPose, "LeftTouch", kLeftHand, kLeftIndex, kButtonX | kButtonY);
    const HandSample right = hand(Hand::Right, kRightPose, "RightTouch", kRightHand, kRightIndex, kButtonA | kButtonB);
    const HeadSample head{t, pose(kHeadPose, "Head")};
    r.hands.push_back(left);
    r.hands.push_back(right);
    r.heads.push_back(head);
  }
  if (r.heads.empty()) throw Error(path + ": no samples after the header");
  return r;
}

Recording import_coremotion_csv(const std::string& path) {
  const std::vector<CoreMotionSample> samples = read_coremotion_csv(path);  // not empty, time non-decreasing
  Recording r;
  r.source = "coremotion";
  r.motion.reserve(samples.size());
  for (const CoreMotionSample& s : samples) {
    MotionSample m;
    m.t = s.time - samples.front().time;
    m.acceleration = s.user_acceleration + s.gravity;  // the raw accelerometer, as CoreMotion defines it
    m.has_rotation_rate = true;
    m.rotation_rate = s.rotation_rate;
    r.motion.push_back(m);
  }
  return r;
}

}  // namespace wedge::recordings
