// A scene's "interaction" block (how hands and a phone reach it, docs/input.md) as the input layer's
// settings: what `wedge replay`, `wedge view` and `wedge xr` give their input session.
#pragma once

#include "wedge/input/session.hpp"
#include "wedge/scenes/scene.hpp"

namespace wedge::scenes {

template <int N>
input::InteractionSettings<N> interaction_settings(const Scene<N>& scene) {
  input::InteractionSettings<N> s;
  s.tracking.origin = scene.interaction.origin;
  s.tracking.scale = scene.interaction.scale;
  s.grab_radius = scene.interaction.grab_radius;
  s.gravity_tilt_on = scene.interaction.gravity_tilt_on;
  s.gravity_tilt_degrees = scene.interaction.gravity_tilt;
  return s;
}

// The session settings of a scene at step h (s): its interaction block, and h (the scene's "timestep"
// unless the caller chooses another).
template <int N>
input::SessionSettings<N> session_settings(const Scene<N>& scene, double h) {
  input::SessionSettings<N> s;
  s.interaction = interaction_settings(scene);
  s.timestep = h;
  return s;
}

}  // namespace wedge::scenes
