// The viewer's session (`wedge view`): the world and what steps it. Recordings (--replay) drive
// it through ReplayInput, as `wedge replay` does; otherwise the mouse hand and the phone do, as the right
// hand and the accelerometer of an input layer of the viewer's own, whose frames --record writes down.
// Either way every step goes through input::Session, paid for by a clock (the accumulator), and its
// grabs, releases and haptic pulses go to the --events file and to what the screen shows of pulses.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "event_json.hpp"
#include "json_out.hpp"
#include "replay_input.hpp"
#include "view_mouse.hpp"
#include "wedge/recordings/recording.hpp"
#include "wedge/scenes/interaction.hpp"
#include "wedge/slicing/world_slices.hpp"

namespace wedge::cli::viewer {

// What the viewer shows of haptic pulses, which a mouse and a screen cannot feel: a line each in the
// panel's log, and for a quarter second a flash at the contact point and on the hand's marker.
template <int N>
struct PulseDisplay {
  std::vector<std::string> log;
  std::vector<std::pair<Vec<N>, double>> flashes;      // haptic pulses shown: contact point, until (s)
  std::array<double, input::kHandCount> hand_flash{};  // a hand's marker flashes until this time (s)
};

template <int N>
class ViewSession {
 public:
  // The scene's world, and the recordings that drive it (refused here if they cannot mean anything in
  // the scene). `record`: the --record file, or empty.
  ViewSession(const Scene<N>& scene, const std::string& file, const std::vector<std::string>& replay_files,
              const std::string& record)
      : scene_(scene),
        file_(file),
        replay_files_(replay_files),
        record_path_(record),
        h_(scene.timestep),
        world_(scene.make_world(file)) {
    if (!replay_files_.empty()) replay_ = std::make_unique<ReplayInput<N>>(scene_, world_, replay_files_, file_, h_);
  }
  ViewSession(const ViewSession&) = delete;
  ViewSession& operator=(const ViewSession&) = delete;

  // Once the window is open: the mouse's input layer (unless recordings drive the world), over `slices`,
  // the viewed slice; and the --events file (`events`; empty: none).
  void start(const slicing::WorldSlices<N>& slices, const std::string& events) {
    slices_ = &slices;
    if (recording() && !replay_) open_recording();
    if (!replay_) mouse_in_ = mouse_layer();
    // --events: grabs, releases, pulses as `wedge replay --events` writes them
    if (!events.empty()) events_ = std::make_unique<OutputSink>(events);
  }

  World<N>& world() { return world_; }
  const World<N>& world() const { return world_; }
  bool mouse_driven() const { return bool(mouse_in_); }
  // The recordings' hands, or nothing when the mouse drives the world.
  const input::Interaction<N>* recorded_hands() const { return replay_ ? &replay_->interaction() : nullptr; }
  PulseDisplay<N>& pulses() { return pulses_; }
  const PulseDisplay<N>& pulses() const { return pulses_; }

  // The slice moved: the mouse's tracking space follows it (unless recording, see mouse_layer), so the
  // hand moves with the slice. Only while the hand holds nothing.
  void follow_slice() {
    if (mouse_in_ && !recording()) mouse_in_ = mouse_layer();
  }

  // Back to the scene's start: a new world, the recordings from their beginning (or a new mouse layer), no
  // clock debt, and the recording emptied (a recording starts with the world it replays into).
  void reset() {
    world_ = scene_.make_world(file_);
    replay_.reset();
    if (!replay_files_.empty()) replay_ = std::make_unique<ReplayInput<N>>(scene_, world_, replay_files_, file_, h_);
    mouse_in_.reset();
    if (!replay_) mouse_in_ = mouse_layer();
    if (writer_) open_recording();  // emptied: it starts again with the new world
    pending_ = 0.0;
  }

  // The accumulator: `dt` s of simulated time owed to the clock; steps_owed() takes the steps that pay
  // for it (and one more for `single`), at most 64 a frame: too slow to keep up, the debt is dropped
  // rather than spiral.
  void owe(double dt) { pending_ += dt; }
  int steps_owed(bool single) {
    int steps = single ? 1 : 0;
    for (; pending_ >= h_ && steps < 64; pending_ -= h_) ++steps;
    if (steps == 64) pending_ = 0.0;  // too slow to keep up: drop the debt rather than spiral
    return steps;
  }

  // One step, its input from the recordings or else from the mouse hand and the phone; its grabs,
  // releases and pulses logged.
  void step(const MouseHand& hand, const Phone& phone) {
    if (replay_) {
      replay_->step();
      log_events(replay_->session());
      return;
    }
    input::InputFrame input_frame;
    input_frame.t = double(world_.step_count()) * h_;
    input::HandInput& right = input_frame.hands[1];
    right.tracked = hand.ever;
    right.position = to_tracking(hand.point);
    right.orientation = hand.turn;
    right.squeeze = hand.holding ? 1.0 : 0.0;
    right.mode4d = hand.mode4d;
    recordings::MotionSample motion;
    if (phone.active) {
      motion.t = input_frame.t;
      motion.acceleration = phone.acceleration();
      motion.tilt = phone.tilt_w;
      input_frame.motion = std::span<const recordings::MotionSample>(&motion, 1);
    }
    mouse_in_->step(input_frame);
    log_events(*mouse_in_);
  }

  // On exit: the --events file put in place, the --record recording closed (synced).
  void finish() {
    if (events_) events_->commit();
    if (writer_) {
      try {
        writer_->close();
      } catch (const Error& e) {
        throw Failure(e.what());
      }
    }
  }

 private:
  bool recording() const { return !record_path_.empty(); }

  // The mouse as the right hand of an input layer of its own. Its tracking space is the scene's, with
  // the hidden coordinates moved to the viewed slice (origin: the slice's hidden offsets), unless
  // recording: a recording has no slice offsets, so then the hand stays in the scene's own slice and its
  // samples mean the same to `wedge replay`. Recording, each step's frame is kept: one sample per step,
  // at its time, so that replay reads it back exactly.
  std::unique_ptr<input::Session<N>> mouse_layer() {
    input::SessionSettings<N> settings = scenes::session_settings(scene_, h_);
    if (!recording())
      for (int a = 3; a < N; ++a) settings.interaction.tracking.origin[a] = slices_->flat().origin[a];
    auto session = std::make_unique<input::Session<N>>(world_, settings);
    session->set_step_function([this](World<N>& stepped, double step) { checked_step(stepped, step, file_); });
    if (recording())  // one sample per step, at its time: replay reads it back exactly
      session->set_observer([this](const input::InputFrame& f) { record_frame(f); });
    return session;
  }

  // --record: a frame's accelerometer samples and its right hand, while tracked, each written as a whole,
  // flushed line (a session killed at any moment leaves every sample before it).
  void record_frame(const input::InputFrame& f) { writer_->write_frame(f); }

  // (Re)creates the --record file, empty but for its header.
  void open_recording() {
    try {
      writer_.reset();
      writer_.emplace(record_path_, "viewer");
    } catch (const Error& e) {
      throw Failure(e.what());
    }
  }

  // Slice coordinates of the hand -> tracking coordinates of the scene's interaction.
  Eigen::Vector3d to_tracking(const Eigen::Vector3d& p) const {
    Eigen::Vector3d t = p;
    for (int a = 0; a < std::min(N, 3); ++a)
      t[a] = (slices_->flat().origin[a] + p[a] - scene_.interaction.origin[a]) / scene_.interaction.scale;
    return t;
  }

  // A session's grabs, releases and pulses since the last call: to the --events file and the pulse
  // display; the session's output is cleared.
  void log_events(input::Session<N>& session) {
    for (const input::HapticPulse<N>& p : session.pulses()) log_pulse(p);
    if (events_)
      for (const input::InteractionEvent<N>& e : session.events()) events_->write_line(event_json(world_, e).dump());
    session.clear_output();
  }
  // The panel's log, flashes at the contact and hand; the event line.
  void log_pulse(const input::HapticPulse<N>& p) {
    char line[160];
    std::snprintf(line, sizeof line, "t %.2f s: %s hand, %s on %s, %.2f", p.t, hand_name(p.hand),
                  world_.name(p.held).c_str(), world_.name(p.other).c_str(), p.amplitude);
    pulses_.log.emplace_back(line);
    pulses_.flashes.emplace_back(p.point, world_.time() + 0.25);
    pulses_.hand_flash[std::size_t(p.hand)] = world_.time() + 0.25;
    if (events_) events_->write_line(pulse_json(world_, p).dump());
  }

  const Scene<N>& scene_;
  const std::string& file_;
  const std::vector<std::string>& replay_files_;
  const std::string& record_path_;
  const double h_;
  World<N> world_;  // (the sessions below hold references to it: it is reset in place)
  // --replay: the recordings' session (not std::optional: GCC 12 warns falsely about its reset)
  std::unique_ptr<ReplayInput<N>> replay_;
  std::unique_ptr<input::Session<N>> mouse_in_;  // without recordings: the mouse's
  const slicing::WorldSlices<N>* slices_ = nullptr;  // the viewed slice (from start() on)
  std::optional<recordings::RecordingWriter> writer_;  // --record: the mouse hand (and the phone), line by line
  double pending_ = 0.0;                             // s of simulated time owed to the clock
  std::unique_ptr<OutputSink> events_;               // --events
  PulseDisplay<N> pulses_;
};

}  // namespace wedge::cli::viewer
