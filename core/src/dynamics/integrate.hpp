// Body integration (internal), shared by World's stages and the soft step's (contact/soft_step.cpp):
// symplectic Euler, the velocity half first, then the position half with the new velocities.
#pragma once

#include "wedge/body.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"
#include "wedge/world.hpp"

namespace wedge::dynamics {

// What the velocity half integrates with: WorldSettings' gravity and gyroscopic settings.
template <int N>
struct Motion {
  Vec<N> gravity = Vec<N>::Zero();  // m/s^2
  bool gyroscopic = true;
  GyroscopicMethod gyroscopic_method = GyroscopicMethod::ImplicitMidpoint;
};
template <int N>
Motion<N> motion_of(const WorldSettings<N>& s) {
  return {s.gravity, s.gyroscopic, s.gyroscopic_method};
}

// Whether the body's angular velocity changes other than by drag: it has a torque, or a gyroscopic
// term (an inertia that is not the same about every plane; for a cube or a ball w x I w = 0).
template <int N>
bool needs_body_frame(const Body<N>& b, const Motion<N>& motion);

// Body b's velocities v, w (its own, or the soft step's solver body's) over h: v += h (g + F/m);
// where needs_body_frame, in the body frame, whose inertia is constant, w_b += h I^-1 ~R tau R and then
// the gyroscopic term implicitly (gyroscopic_step); then drag as an implicit decay 1/(1 + h c), stable
// for any h.
template <int N>
void integrate_velocity(const Body<N>& b, const Motion<N>& motion, double h, Vec<N>& v, Bivector<N>& w);

// The position half: x += h v, R <- exp(-h w/2) R (exact for constant w over h), and, when repair_now,
// R rebuilt from unit-vector factors (its drift from a rotation removed).
template <int N>
inline void advance_body(Body<N>& b, const Vec<N>& v, const Bivector<N>& w, double h, bool repair_now) {
  b.center += h * v;
  b.rotor = exp<N>(w * (-0.5 * h)) * b.rotor;
  if (repair_now) b.rotor = repair(b.rotor);
}

}  // namespace wedge::dynamics
