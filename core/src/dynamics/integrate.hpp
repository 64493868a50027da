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

// What the velocity half does to a body's angular velocity, read off its torque and inertia once (the
// soft step integrates a body once per sub-step; its k x k inertia is then not read again).
template <int N>
struct AngularModel {
  bool body_frame = false;  // needs_body_frame: a torque or a gyroscopic term acts
  bool torque = false;      // a torque acts
  bool gyroscopic = false;  // the gyroscopic term is integrated (WorldSettings::gyroscopic)
  bool diagonal = false;    // ... by the midpoint rule, and the body-frame inertia is diagonal: these moments, kg m^2
  Bivector<N> moments;
};
template <int N>
AngularModel<N> angular_model(const Body<N>& b, const Motion<N>& motion);

// Body b's velocities v, w (its own, or the soft step's solver body's) over h: v += h (g + F/m);
// where needs_body_frame, in the body frame, whose inertia is constant, w_b += h I^-1 ~R tau R and then
// the gyroscopic term implicitly (gyroscopic_step); then drag as an implicit decay 1/(1 + h c), stable
// for any h. The second form takes the body's angular_model, found before.
template <int N>
void integrate_velocity(const Body<N>& b, const Motion<N>& motion, double h, Vec<N>& v, Bivector<N>& w);
template <int N>
void integrate_velocity(const Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h, Vec<N>& v,
                        Bivector<N>& w);

// The position half: x += h v, R <- exp(-h w/2) R (exact for constant w over h), and, when repair_now,
// R rebuilt from unit-vector factors (its drift from a rotation removed).
template <int N>
inline void advance_body(Body<N>& b, const Vec<N>& v, const Bivector<N>& w, double h, bool repair_now) {
  b.center += h * v;
  b.rotor = exp<N>(w * (-0.5 * h)) * b.rotor;
  if (repair_now) b.rotor = repair(b.rotor);
}

}  // namespace wedge::dynamics
