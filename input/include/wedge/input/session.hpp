// One interactive session: input frames in, the world stepped at its fixed rate, events and pulses out.
//
//   frame at t = k h ──> Interaction::before_step ──> World::step(h) ──> Interaction::after_step
//   (a recording, the mouse,     (grabs, torques, gravity)                  (haptic pulses from the
//    an OpenXR runtime)                                                      step's contact events)
//
// The three front ends (`wedge replay`, `wedge view`, `wedge xr`) drive a World only through this loop, so
// a live session and the replay of its recording run the same code. Step k starts at t = k h (k is the
// world's step count); `advance` runs the steps that a clock's elapsed time pays for (an accumulator), and
// `step` runs one with a given frame. The grabs, releases and pulses of the steps since the last
// clear_output() are kept in order for the front end to write, draw or send to a device.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "wedge/input/frame.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/world.hpp"

namespace wedge::input {

template <int N>
struct SessionSettings {
  InteractionSettings<N> interaction;
  double timestep = 1.0 / 120.0;  // s: h, the fixed step
  int max_steps_per_advance = 64;  // a clock that runs ahead of the physics by more is forgiven, not chased
};

template <int N>
class Session {
 public:
  // Called with the world and h to take one step (default: World::step). Front ends wrap it with their
  // checks (Ctrl-C, non-finite states).
  using StepFunction = std::function<void(World<N>&, double)>;
  // Called with each step's frame just before it is applied (a recorder).
  using FrameObserver = std::function<void(const InputFrame&)>;

  // Throws wedge::Error for invalid settings (Interaction's, h not finite and > 0, max steps < 1).
  Session(World<N>& world, const SessionSettings<N>& settings);

  void set_step_function(StepFunction f) { step_function_ = std::move(f); }
  void set_observer(FrameObserver f) { observer_ = std::move(f); }

  // One step, the frame applied before it. frame.t should be time() (the step's start).
  void step(const InputFrame& frame);

  // Adds dt (s, >= 0) of a clock to the accumulator and runs the steps it pays for, each with frame_at(t)
  // at its start time t; returns how many ran. At most max_steps_per_advance run: the rest of the debt is
  // dropped (a clock far ahead of the physics would otherwise spiral).
  template <class FrameAt>
  int advance(double dt, FrameAt&& frame_at) {
    pending_ += dt;
    int steps = 0;
    for (; pending_ >= h_; pending_ -= h_) {
      if (steps == settings_.max_steps_per_advance) {
        pending_ = 0.0;
        break;
      }
      step(frame_at(time()));
      ++steps;
    }
    return steps;
  }

  double timestep() const { return h_; }
  std::int64_t step_count() const { return world_.step_count(); }
  double time() const { return double(world_.step_count()) * h_; }  // s: the next step's start, k h

  // What the steps since the last clear_output() produced, in order.
  const std::vector<InteractionEvent<N>>& events() const { return events_; }
  const std::vector<HapticPulse<N>>& pulses() const { return pulses_; }
  void clear_output();

  const Interaction<N>& interaction() const { return interaction_; }
  // Moves the tracking space between steps (Interaction::set_tracking_origin).
  void set_tracking_origin(const Vec<N>& origin) { interaction_.set_tracking_origin(origin); }
  World<N>& world() { return world_; }
  const World<N>& world() const { return world_; }

 private:
  World<N>& world_;
  SessionSettings<N> settings_;
  double h_;
  Interaction<N> interaction_;
  StepFunction step_function_;
  FrameObserver observer_;
  double pending_ = 0.0;
  std::vector<InteractionEvent<N>> events_;
  std::vector<HapticPulse<N>> pulses_;
};

}  // namespace wedge::input
