// The input layer: hands and an accelerometer drive a World between its steps (paper section 8).
//
//   device sample -> InputFrame -> Interaction::before_step -> World::step -> Interaction::after_step
//                                  (grabs, torques, gravity)                  (haptic pulses from the
//                                                                              step's contact begin events)
// before_step runs three named stages: update_gravity, track_hands, grab_and_release, drive_held.
// Nothing here allocates per step once the event buffers have grown; the core knows nothing of it.
//
// Conventions: hands are indexed by int(Hand) (0 left, 1 right). Events carry `step`, the
// index of the step they belong to (a grab or release is applied before step k; a haptic pulse comes
// from the contact that began during step k), and `t`, that step's start time k h.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "wedge/input/frame.hpp"
#include "wedge/input/gravity_filter.hpp"
#include "wedge/input/tracking_space.hpp"
#include "wedge/world.hpp"

namespace wedge::input {

template <int N>
struct InteractionSettings {
  TrackingSpace<N> tracking;
  // Grab: squeeze past squeeze_on grabs, below squeeze_off lets go (hysteresis against a trembling
  // finger); the body containing the hand's point, else the nearest within grab_radius.
  double squeeze_on = 0.6, squeeze_off = 0.4;
  double grab_radius = 0.05;             // m, world
  double follow_frequency = 8.0;         // Hz: the grab spring (wedge/grab.hpp)
  double follow_damping_ratio = 1.0;
  double follow_max_acceleration = 300.0;  // m/s^2: force limit = mass * this
  // Rotation drive: a PD torque, implicit like the grab spring, scaled by the world inertia.
  double turn_frequency = 4.0;            // Hz
  double turn_damping_ratio = 1.0;
  double turn_max_acceleration = 200.0;   // rad/s^2: torque limit = I' * this
  // Haptics: one pulse per contact begin event of a held body.
  double pulse_full_speed = 2.0;         // m/s: approach speed that gives amplitude 1
  double pulse_min_amplitude = 0.1;      // amplitude of a contact that begins at rest
  double pulse_duration = 0.03;          // s
  double pulse_min_interval = 0.05;      // s: per hand; pulses sooner than this after the last are dropped
  // Gravity from the accelerometer: direction from the filter, magnitude |scene gravity|.
  bool gravity_tilt_on = false;          // the tilt toward w is on from the start (a recorded flag turns it)
  double gravity_tilt_degrees = 15.0;    // [0, 90]
  double gravity_time_constant = 5.0;    // s, with a gyro (GravityFilter)
  double gravity_time_constant_accel_only = 0.25;  // s, for devices that record no rotation rate
};

template <int N>
struct HapticPulse {
  int hand = 0;
  double amplitude = 0.0;   // [0, 1]
  double duration = 0.0;    // s
  double frequency = 0.0;   // Hz; 0 = the runtime's default (XR_FREQUENCY_UNSPECIFIED)
  BodyId held, other;       // the held body and what it touched
  Vec<N> point = Vec<N>::Zero();  // m, world: where they touched
  double approach_speed = 0.0;    // m/s
  double t = 0.0;
  std::int64_t step = 0;
};

template <int N>
struct InteractionEvent {
  enum class Kind : std::uint8_t { Grab, Release };
  Kind kind = Kind::Grab;
  int hand = 0;
  BodyId body;
  Vec<N> point = Vec<N>::Zero();        // grab: m, world (the grab point)
  Vec<N> local_point = Vec<N>::Zero();  // grab: m, body frame
  Vec<N> velocity = Vec<N>::Zero();     // release: m/s, of the centre of mass
  Bivector<N> angular_velocity{};       // release: rad/s, world
  double t = 0.0;
  std::int64_t step = 0;
};

template <int N>
class Interaction {
 public:
  // Throws wedge::Error for invalid settings (thresholds out of order, non-positive rates, tilt > 90).
  Interaction(World<N>& world, const InteractionSettings<N>& settings);

  // Applies one frame between steps, h being the step that follows.
  void before_step(const InputFrame& frame, double h);
  // Reads the step's contact begin events into haptic pulses.
  void after_step();

  // Moves the tracking space's origin (m, world), as moving the slice along w does when the hands follow
  // it: a hand keeps its tracking coordinates, so its world point moves by the change, and the change is
  // not taken for a motion (no velocity from it). A held body is pulled along by its grab spring.
  void set_tracking_origin(const Vec<N>& origin);

  // What the last before_step / after_step produced (cleared at each call; no allocation once grown).
  const std::vector<InteractionEvent<N>>& events() const { return events_; }
  const std::vector<HapticPulse<N>>& pulses() const { return pulses_; }
  std::int64_t dropped_pulses() const { return dropped_pulses_; }  // by the rate limit, in total

  // A hand's state after the last before_step.
  bool tracked(int hand) const { return hands_[hand].tracked; }
  const Vec<N>& hand_point(int hand) const { return hands_[hand].point; }  // m, world
  const Rotor<N>& hand_frame(int hand) const { return hands_[hand].frame; }  // its N-D orientation
  std::optional<BodyId> held(int hand) const;
  std::optional<GrabId> grab(int hand) const;
  bool gravity_tilt_on() const { return tilt_on_; }
  const InteractionSettings<N>& settings() const { return settings_; }

 private:
  struct HandState {
    bool tracked = false, pressed = false, holding = false;
    Vec<N> point = Vec<N>::Zero(), velocity = Vec<N>::Zero();
    Rotor<N> frame = Rotor<N>::identity();  // the hand's N-D orientation (4D turns accumulate in it)
    Bivector<N> spin{};                     // rad/s, world: its rate of turn
    Eigen::Quaterniond last_orientation = Eigen::Quaterniond::Identity();
    GrabId grab;
    BodyId body;
    Rotor<N> offset = Rotor<N>::identity();  // ~frame R_body at the grab: the body's turn relative to the hand
    double last_pulse = -std::numeric_limits<double>::infinity();
  };

  void update_gravity(const InputFrame& frame);
  void track_hands(const InputFrame& frame, double h);
  void grab_and_release(const InputFrame& frame);
  void drive_held(double h);
  void release(int hand);
  InteractionEvent<N>& new_event(typename InteractionEvent<N>::Kind kind, int hand, BodyId body);

  World<N>& world_;
  InteractionSettings<N> settings_;
  std::array<HandState, kHandCount> hands_;
  std::optional<GravityFilter> filter_;
  double last_motion_t_ = 0.0;
  double gravity_magnitude_ = 0.0;
  bool tilt_on_ = false;
  double t_ = 0.0, h_ = 0.0;
  std::vector<InteractionEvent<N>> events_;
  std::vector<HapticPulse<N>> pulses_;
  std::int64_t dropped_pulses_ = 0;
};

// The gravity the input layer sets (m/s^2): |g| times the device's gravity direction d (unit, device
// frame: x right, y up, z out of the screen) laid along the world's first three axes, turned toward +w
// (the last axis) by tilt_degrees when the tilt is on: |g| (cos a d + sin a e_w). In 2D d_z is dropped;
// below 4D there is no w and the tilt must be off. Zero if d is zero (in 2D: d along z).
template <int N>
Vec<N> gravity_from_device(const Eigen::Vector3d& direction, double magnitude, bool tilt_on, double tilt_degrees);

// The haptics rule: amplitude from the approach speed, rising linearly from min_amplitude at rest to 1 at
// full_speed and beyond.
double pulse_amplitude(double approach_speed, double full_speed, double min_amplitude);

}  // namespace wedge::input
