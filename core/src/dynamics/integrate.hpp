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

// What the velocity half does to a body's angular velocity, read off its torque and inertia once (the
// soft step integrates a body once per sub-step; its k x k inertia is then not read again).
template <int N>
struct AngularModel {
  // The angular velocity changes other than by drag: a torque acts, or a gyroscopic term (an inertia
  // that is not the same about every plane; for a cube or a ball w x I w = 0).
  bool body_frame = false;
  bool torque = false;      // a torque acts
  bool gyroscopic = false;  // the gyroscopic term is integrated (WorldSettings::gyroscopic)
  bool diagonal = false;    // ... by the midpoint rule, and the body-frame inertia is diagonal: these moments, kg m^2
  Bivector<N> moments;
};
template <int N>
AngularModel<N> angular_model(const Body<N>& b, const Motion<N>& motion);

// Body b's velocities v, w (its own, or the soft step's solver body's) over h: v += h (g + F/m);
// where the model has body_frame, in the body frame, whose inertia is constant, w_b += h I^-1 ~R tau R
// and then the gyroscopic term implicitly (gyroscopic_step); then drag as an implicit decay
// 1/(1 + h c), stable for any h. The second form takes the body's angular_model, found before.
template <int N>
void integrate_velocity(const Body<N>& b, const Motion<N>& motion, double h, Vec<N>& v, Bivector<N>& w);
template <int N>
void integrate_velocity(const Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h, Vec<N>& v,
                        Bivector<N>& w);

// The angular part of integrate_velocity where the model has body_frame, on the body-frame angular
// velocity w_b = ~R w R: w_b += h I^-1 ~R tau R, then the gyroscopic term implicitly.
template <int N>
void integrate_body_frame(const Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h,
                          Bivector<N>& wb);

// `substeps` sub-steps of h, each the velocity half and then the position half, of a body (its
// velocities v, w) that nothing else acts on in between, with the angular velocity kept in the body
// frame throughout (w_b = ~R w R, two sandwiches a step instead of two a sub-step): the rotor moves by
// R <- R exp(-h w_b / 2), which is exp(-h w / 2) R, as R exp(B) ~R = exp(R B ~R). Where the model has no
// body_frame, w only decays, every sub-step's turn lies in the plane of the first, and the turns
// compose to one: R <- exp(-h (w_1 + ... + w_n) / 2) R, exactly (parallel bivectors commute), one exp a
// step. When repair_at_end, the rotor is repaired after the last sub-step.
template <int N>
void advance_alone(Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h, int substeps,
                   bool repair_at_end, Vec<N>& v, Bivector<N>& w);

// The position half: x += h v, R <- exp(-h w/2) R (exact for constant w over h), and, when repair_now,
// R rebuilt from unit-vector factors (its drift from a rotation removed).
template <int N>
inline void advance_body(Body<N>& b, const Vec<N>& v, const Bivector<N>& w, double h, bool repair_now) {
  b.center += h * v;
  b.rotor = exp<N>(w * (-0.5 * h)) * b.rotor;
  if (repair_now) b.rotor = repair(b.rotor);
}

}  // namespace wedge::dynamics
