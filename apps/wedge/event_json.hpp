// The input layer's events as JSON lines, shared by `wedge replay --events` and `wedge view --events`
// (docs/scene-format.md, "Replay output"): grab and release (kind, time, step, hand, body, and the grab
// point or the velocities at release) and haptic pulses (amplitude, duration, frequency, the two bodies,
// the contact point and the approach speed).
#pragma once

#include "json_out.hpp"
#include "wedge/input/interaction.hpp"

namespace wedge::cli {

inline const char* hand_name(int hand) { return hand == 0 ? "left" : "right"; }

template <int N>
OutJson event_json(const World<N>& world, const input::InteractionEvent<N>& e) {
  const bool grab = e.kind == input::InteractionEvent<N>::Kind::Grab;
  OutJson j;
  j["type"] = grab ? "grab" : "release";
  j["t"] = e.t;
  j["step"] = e.step;
  j["hand"] = hand_name(e.hand);
  j["body"] = world.name(e.body);
  if (grab) {
    j["point"] = to_json(e.point);
    j["local_point"] = to_json(e.local_point);
  } else {
    j["velocity"] = to_json(e.velocity);
    j["angular_velocity"] = to_json(e.angular_velocity);
  }
  return j;
}

template <int N>
OutJson pulse_json(const World<N>& world, const input::HapticPulse<N>& p) {
  OutJson j;
  j["type"] = "haptic";
  j["t"] = p.t;
  j["step"] = p.step;
  j["hand"] = hand_name(p.hand);
  j["amplitude"] = p.amplitude;
  j["duration"] = p.duration;
  j["frequency"] = p.frequency;
  j["bodies"] = OutJson::array({world.name(p.held), world.name(p.other)});
  j["point"] = to_json(p.point);
  j["approach_speed"] = p.approach_speed;
  return j;
}

}  // namespace wedge::cli
