// The session loop (session.hpp).
#include "wedge/input/session.hpp"

#include <cmath>

#include "wedge/error.hpp"

namespace wedge::input {

namespace {
template <int N>
const SessionSettings<N>& checked(const SessionSettings<N>& s) {
  if (!(s.timestep > 0.0) || !std::isfinite(s.timestep)) throw Error("session settings: timestep must be finite and > 0 (s)");
  if (s.max_steps_per_advance < 1) throw Error("session settings: max_steps_per_advance must be >= 1");
  return s;
}
}  // namespace

template <int N>
Session<N>::Session(World<N>& world, const SessionSettings<N>& settings)
    : world_(world), settings_(checked(settings)), h_(settings.timestep), interaction_(world, settings.interaction) {
  events_.reserve(8);
  pulses_.reserve(8);
}

template <int N>
void Session<N>::step(const InputFrame& frame) {
  if (observer_) observer_(frame);
  interaction_.before_step(frame, h_);
  events_.insert(events_.end(), interaction_.events().begin(), interaction_.events().end());
  if (step_function_)
    step_function_(world_, h_);
  else
    world_.step(h_);
  interaction_.after_step();
  pulses_.insert(pulses_.end(), interaction_.pulses().begin(), interaction_.pulses().end());
}

template <int N>
void Session<N>::clear_output() {
  events_.clear();
  pulses_.clear();
}

template class Session<2>;
template class Session<3>;
template class Session<4>;
template class Session<5>;
template class Session<6>;

}  // namespace wedge::input
