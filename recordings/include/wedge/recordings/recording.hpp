// Wedge's own recording format (JSON Lines, docs/recording-format.md): what any device or script did,
// as timed samples of hands, head and phone motion, in one set of units and frames. Importers turn other
// devices' files into it; replay (apps/wedge) and the tests read it back.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace wedge::recordings {

enum class Hand : std::uint8_t { Left = 0, Right = 1 };

// Buttons: the Oculus SDK TouchButtons bits (A = 0x1, B = 0x2, X = 0x100, Y = 0x200); other bits are not kept.
inline constexpr std::uint32_t kButtonA = 0x1, kButtonB = 0x2, kButtonX = 0x100, kButtonY = 0x200;

struct Pose {  // tracking space: metres, OpenXR convention (x right, y up, z toward the user)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // unit; local -> tracking
};

struct HandSample {
  double t = 0.0;  // s on the recording's clock (importers start it at 0)
  Hand hand = Hand::Right;
  Pose pose;
  double squeeze = 0.0;       // [0, 1] grip ("hand trigger")
  double trigger = 0.0;       // [0, 1] index trigger
  std::uint32_t buttons = 0;  // kButton* bits
  bool mode4d = false;        // the recording's own 4D-rotation flag (besides A / X)
};

struct HeadSample {
  double t = 0.0;
  Pose pose;
};

struct MotionSample {
  double t = 0.0;
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // g, device frame (x right, y up, z out of the screen),
                                   // gravity included and pointing the way it pulls (CoreMotion's sign: a
                                   // still phone held upright reads (0, -1, 0))
  bool has_rotation_rate = false;
  Eigen::Vector3d rotation_rate = Eigen::Vector3d::Zero();  // rad/s, device frame
  bool tilt = false;  // the paper's gravity-tilt button (tilt toward w)
};

struct Recording {
  std::string source;                 // "quest2-touch", "coremotion", "script", "viewer", ...
  std::vector<HandSample> hands;      // in file order (time non-decreasing)
  std::vector<HeadSample> heads;
  std::vector<MotionSample> motion;
  std::vector<std::string> warnings;  // e.g. "FILE:LINE: torn last line (cut off mid-write), ignored"
  double duration() const;            // last sample time of any stream (0 for an empty recording)
};

inline constexpr int kRecordingVersion = 1;

// Throws wedge::Error "PATH:LINE: problem" for anything but a well-formed version-1 recording; a torn last
// line (no '\n', not JSON: the writer was cut off) is dropped with a warning instead.
Recording read_recording(const std::string& path);
// Atomic (a temporary file renamed into place): the file is whole or absent. Samples are merged by time
// (hands before heads before motion at equal times). Throws wedge::Error on an I/O error, or for a sample
// the reader would refuse (non-finite, negative or decreasing time, triggers outside [0, 1]).
void write_recording(const std::string& path, const Recording& r);

Recording import_questset_csv(const std::string& path);    // Quest 2 Touch CSV (questset layout)
Recording import_coremotion_csv(const std::string& path);  // iPhone CoreMotion CSV (uses read_coremotion_csv)

}  // namespace wedge::recordings
