// Wedge's own recording format (JSON Lines, docs/recording-format.md): what any device or script did,
// as timed samples of hands, head and phone motion, in one set of units and frames. Importers turn other
// devices' files into it; replay (apps/wedge) and the tests read it back.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "wedge/input/frame.hpp"
#include "wedge/input/samples.hpp"

namespace wedge::recordings {

// The device sample types are the input layer's (wedge/input/samples.hpp); this library writes and reads them.
using input::Hand;
using input::HandSample;
using input::HeadSample;
using input::kButtonA;
using input::kButtonB;
using input::kButtonX;
using input::kButtonY;
using input::MotionSample;
using input::Pose;

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

// A recording written as it happens (a live session's --record): the header at once, then each sample
// as one line, written and flushed as it comes, so that a session cut off (Ctrl-C, a crash) leaves every
// sample it took but at most a torn last line, which read_recording drops with a warning. Samples must
// come in time order; each is checked as write_recording checks it (throws wedge::Error "PATH: ...").
class RecordingWriter {
 public:
  RecordingWriter(const std::string& path, const std::string& source);  // creates or truncates PATH
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  void write(const HandSample& s);
  void write(const HeadSample& s);
  void write(const MotionSample& s);
  // A step's input as samples: its accelerometer samples, then each tracked hand at frame.t (replay's
  // frame_at(t) reads exactly these values back).
  void write_frame(const input::InputFrame& frame);
  std::int64_t samples() const;
  void close();  // syncs and closes; throws wedge::Error on an I/O error

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

Recording import_questset_csv(const std::string& path);    // Quest 2 Touch CSV (questset layout)
Recording import_coremotion_csv(const std::string& path);  // iPhone CoreMotion CSV (uses read_coremotion_csv)

}  // namespace wedge::recordings
