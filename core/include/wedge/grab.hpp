// Grabs: a soft point constraint that pulls a point of a dynamic body toward a moving target (a hand),
// solved with the contacts (a mouse joint in Box2D's sense, a spring and damper in Jolt's). The body
// keeps colliding while held: contacts are solved after the grab in every pass, so a held body is
// stopped by static bodies and heavy piles instead of crushing them, and pushes light bodies aside.
//
// The spring is implicit (wedge/softness.hpp, the coefficients of make_softness(frequency, damping_ratio,
// h)); each pass applies
//   j = -mass_scale K^-1 (v_point - v_target + bias_rate C) - impulse_scale j_accumulated,  C = point - target,
// K being the body's effective mass matrix at the point. That is implicit Euler on a damped spring of
// natural frequency f whatever the body's mass and inertia, so it is stable at any step and behaves
// alike for a 10 g and a 100 kg body. Held still against gravity the point sags by g / (2 pi f)^2 (3.9 mm at the
// default 8 Hz). The accumulated impulse is clamped to mass * max_acceleration * h: a hand cannot lift
// or push more than that, so piles and walls stop it.
#pragma once

#include <cstdint>

#include "wedge/ga/types.hpp"
#include "wedge/contact.hpp"

namespace wedge {

template <int N>
struct GrabDef {
  BodyId body;                                   // a dynamic body
  Vec<N> local_point = Vec<N>::Zero();           // m, the grab point in the body frame (the shape's frame)
  Vec<N> target = Vec<N>::Zero();                // m, world: where the point is pulled
  Vec<N> target_velocity = Vec<N>::Zero();       // m/s, world: how fast the target moves (damped toward it)
  double frequency = 8.0;                        // Hz, > 0: the spring's natural frequency
  double damping_ratio = 1.0;                    // >= 0: 1 is critical damping
  double max_acceleration = 300.0;               // m/s^2, > 0: force limit = body mass * this (~30 g)
};

// A handle to a grab: the slot and the generation it was made in, so a removed grab's id is refused.
struct GrabId {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;
  friend bool operator==(GrabId a, GrabId b) { return a.index == b.index && a.generation == b.generation; }
};

}  // namespace wedge
