// Joints in the soft step (wedge/joint.hpp): each sub-step derives every joint's lever arms, error and
// effective mass from the bodies' poses (prepare_joints), applies its accumulated impulses (warm start)
// and solves it before the contacts in the solve and the relax pass (solve_joints), as Box2D v3 does.
//
// A joint between bodies a and b holds anchor points p_a = x_a + r_a and p_b = x_b + r_b. An impulse j
// on b at p_b (and -j on a at p_a) changes the anchors' relative velocity
//   u = (v_b + r_b . w_b) - (v_a + r_a . w_a)
// by K j, with K = (1/m_a + 1/m_b) 1 + [r_a]_*^T I_a^-1 [r_a]_* + [r_b]_*^T I_b^-1 [r_b]_* (N x N, in any
// dimension: the angular part of an impulse is the bivector r ^ j, wedge_matrix).
//   Point joint:    C = p_b - p_a (N rows),  j = -mass_scale K^-1 (u + bias_rate C) - impulse_scale j_acc.
//   Distance joint: one row along n = C / |C|, C_d = |C| - length, with k = n^T K n; a spring replaces the
//                   joint's stiffness with its own (frequency, damping ratio) in both passes; the limits
//                   are one-sided rows (impulses >= 0), speculative while the distance is inside them.
// In the solve pass the error is corrected at the joint spring's rate (ContactSettings::joint_hertz and
// joint_damping_ratio, wedge/softness.hpp); the relax pass solves the velocity rows alone (no bias, full
// mass), so the correction leaves no velocity behind.
#include <algorithm>
#include <cmath>

#include "contact/contact_system.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/softness.hpp"

namespace wedge::contact {

namespace {

// The two bodies of a joint as the passes see them; the world (a = -1) is a body at rest that no
// impulse moves.
template <int N>
struct JointBodiesView {
  SolverBody<N>* a;  // nullptr: the world
  SolverBody<N>* b;
  const BodyMass<N>* ma;
  const BodyMass<N>* mb;
};

template <int N>
JointBodiesView<N> view(ContactState<N>& s, const JointConstraint<N>& j) {
  return {j.a >= 0 ? &s.solver_bodies[j.a] : nullptr, &s.solver_bodies[j.b], j.a >= 0 ? &s.masses[j.a] : nullptr,
          &s.masses[j.b]};
}

// u = (v_b + r_b . w_b) - (v_a + r_a . w_a).
template <int N>
Vec<N> relative_anchor_velocity(const JointBodiesView<N>& v, const JointConstraint<N>& j) {
  Vec<N> u = v.b->v + dot<N>(j.rb, v.b->w);
  if (v.a) u -= v.a->v + dot<N>(j.ra, v.a->w);
  return u;
}

// The impulse p on b at its anchor and -p on a at its. A body that does not move this step has zero
// inverse mass and inertia (load_solver_bodies), so its velocities stay as they are.
template <int N>
void apply(const JointBodiesView<N>& v, const JointConstraint<N>& j, const Vec<N>& p) {
  v.b->v += v.mb->inv_mass * p;
  v.b->w.c += angular_change(*v.mb, j.rb, p);
  if (!v.a) return;
  v.a->v -= v.ma->inv_mass * p;
  v.a->w.c -= angular_change(*v.ma, j.ra, p);
}

// K, the anchors' relative effective mass matrix (above).
template <int N>
Mat<N> effective_mass_matrix(const JointBodiesView<N>& v, const JointConstraint<N>& j) {
  Mat<N> k = v.mb->inv_mass * Mat<N>::Identity() + angular_mass_term(*v.mb, j.rb);
  if (v.a) k += v.ma->inv_mass * Mat<N>::Identity() + angular_mass_term(*v.ma, j.ra);
  return k;
}

// The distance joint's total impulse along its axis.
template <int N>
double axial_impulse(const JointConstraint<N>& j) {
  return j.impulse + j.lower_impulse - j.upper_impulse;
}

// The lever arms and the error from the bodies' poses now (and a distance joint's axis).
template <int N>
void place_joint(const std::vector<Body<N>>& bodies, JointConstraint<N>& j) {
  const Body<N>& b = bodies[j.b];
  j.rb = rotate(b.rotor, j.local_b);
  Vec<N> pa = j.local_a;
  j.ra.setZero();
  if (j.a >= 0) {
    const Body<N>& a = bodies[j.a];
    j.ra = rotate(a.rotor, j.local_a);
    pa = a.center + j.ra;
  }
  j.separation = b.center + j.rb - pa;
  if (j.type == JointType::Point) return;
  j.distance = j.separation.norm();
  // (Anchors that meet leave the axis of the last sub-step, or the first axis if there was none.)
  if (j.distance > 1e-12) {
    j.axis = j.separation / j.distance;
  } else if (j.axis.squaredNorm() == 0.0) {
    j.axis = Vec<N>::UnitX();
  }
}

// place_joint, then the effective masses. False if the joint cannot act (K not invertible: neither body
// can move).
template <int N>
bool prepare_joint(ContactState<N>& s, const std::vector<Body<N>>& bodies, JointConstraint<N>& j, double h) {
  place_joint(bodies, j);
  const JointBodiesView<N> v = view(s, j);
  const Mat<N> k = effective_mass_matrix(v, j);
  if (j.type == JointType::Point) {
    j.mass = linalg::inverse<N>(k);
    return all_finite(j.mass) && k.trace() > 0.0;
  }
  const double axial = j.axis.dot(k * j.axis);
  if (!(axial > 0.0)) return false;
  j.axial_mass = 1.0 / axial;
  if (j.spring) j.spring_soft = make_softness(j.frequency, j.damping_ratio, h);
  return std::isfinite(j.axial_mass);
}

// How the anchors' separation bends away from a straight line in the sub-step: the second derivative of
// p_b - p_a, which for anchors turning with their bodies is (r_b . w_b) . w_b - (r_a . w_a) . w_a (d/dt
// of r is r . w).
template <int N>
Vec<N> anchor_curvature(const JointBodiesView<N>& v, const JointConstraint<N>& j) {
  Vec<N> q = dot<N>(Vec<N>(dot<N>(j.rb, v.b->w)), v.b->w);
  if (v.a) q -= dot<N>(Vec<N>(dot<N>(j.ra, v.a->w)), v.a->w);
  return q;
}

// One row along the axis: the impulse that brings the axial velocity plus `ahead` to -bias (softened),
// accumulated in `total` and clamped below at 0 where `one_sided`.
template <int N>
double solve_axial_row(const JointBodiesView<N>& v, JointConstraint<N>& j, double sign, double bias, const Softness& soft,
                       double& total, bool one_sided, double ahead = 0.0) {
  const double u = sign * (j.axis.dot(relative_anchor_velocity(v, j)) + ahead);
  double change = -soft.mass_scale * j.axial_mass * (u + bias) - soft.impulse_scale * total;
  if (one_sided) change = std::max(total + change, 0.0) - total;
  total += change;
  apply(v, j, Vec<N>(sign * change * j.axis));
  return change;
}

// The solve pass aims at the anchors' positions at the end of the sub-step, not at their velocities
// now: a pendulum's anchor moving along its circle leaves the tangent line it starts on by (h^2/2) q.
// Asking for the velocity u + (h/2) q instead of u brings it to the circle; the relax pass, which takes
// the joint as the position update left it, then removes the inward velocity that cost. Without this a
// pendulum loses energy every sub-step, in proportion to (h w)^2 (w its angular speed): a 1 m pendulum
// released at 90 degrees swung 1.4% faster than it should at a 60 Hz step, its amplitude decaying.
template <int N>
void solve_point(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft, bool use_bias, double h) {
  Vec<N> u = relative_anchor_velocity(v, j);
  if (use_bias) u += (0.5 * h) * anchor_curvature(v, j);
  const Vec<N> bias = use_bias ? Vec<N>(soft.bias_rate * j.separation) : Vec<N>(Vec<N>::Zero());
  const double mass_scale = use_bias ? soft.mass_scale : 1.0;
  const double impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  const Vec<N> change = -mass_scale * (j.mass * (u + bias)) - impulse_scale * j.linear_impulse;
  j.linear_impulse += change;
  apply(v, j, change);
}

// The distance's second derivative along a straight-line motion of the anchors, |u_perp|^2 / d, plus
// the anchors' own curvature along the axis: what (h/2) times brings the length at the sub-step's end.
template <int N>
double distance_curvature(const JointBodiesView<N>& v, const JointConstraint<N>& j) {
  if (j.distance <= 1e-12) return 0.0;
  const Vec<N> u = relative_anchor_velocity(v, j);
  const double along = j.axis.dot(u);
  return std::max(u.squaredNorm() - along * along, 0.0) / j.distance + j.axis.dot(anchor_curvature(v, j));
}

template <int N>
void solve_distance(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft, bool use_bias,
                    double h) {
  const Softness rigid{};
  const Softness& correction = use_bias ? soft : rigid;
  const double ahead = use_bias ? 0.5 * h * distance_curvature(v, j) : 0.0;
  if (!j.spring || j.min_length >= j.max_length) {
    const double length = j.spring ? j.min_length : j.length;
    const double bias = use_bias ? soft.bias_rate * (j.distance - length) : 0.0;
    solve_axial_row(v, j, 1.0, bias, correction, j.impulse, false, ahead);
    return;
  }
  if (j.frequency > 0.0)  // (the spring is physics, not a correction: both passes)
    solve_axial_row(v, j, 1.0, j.spring_soft.bias_rate * (j.distance - j.length), j.spring_soft, j.impulse, false);
  // A limit the anchors are still inside may close by its gap in the sub-step and no more (speculative,
  // rigid); one they are beyond is pushed back softly in the solve pass.
  const auto limit = [&](double gap, double sign, double& total) {
    if (gap > 0.0) {
      solve_axial_row(v, j, sign, gap / h, rigid, total, true, ahead);
    } else {
      solve_axial_row(v, j, sign, use_bias ? soft.bias_rate * gap : 0.0, correction, total, true, ahead);
    }
  };
  if (j.min_length > 0.0) limit(j.distance - j.min_length, 1.0, j.lower_impulse);
  if (std::isfinite(j.max_length)) limit(j.max_length - j.distance, -1.0, j.upper_impulse);
}

}  // namespace

template <int N>
bool prepare_joints(ContactState<N>& s, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                    double h) {
  JointSolver<N>& js = s.joints;
  js.any_active = false;
  if (js.slots.empty()) return false;
  js.h = h;
  js.soft = make_softness(std::min(settings.joint_hertz, 0.25 / h), settings.joint_damping_ratio, h);
  for (JointConstraint<N>& j : js.slots) {
    j.active = j.live && (moves(s, bodies, j.b) || (j.a >= 0 && moves(s, bodies, j.a)));
    if (!j.active) continue;
    j.active = prepare_joint(s, bodies, j, h);
    js.any_active = js.any_active || j.active;
  }
  return js.any_active;
}

template <int N>
void warm_start_joints(ContactState<N>& s) {
  for (JointConstraint<N>& j : s.joints.slots) {
    if (!j.active) continue;
    const JointBodiesView<N> v = view(s, j);
    apply(v, j, j.type == JointType::Point ? j.linear_impulse : Vec<N>(axial_impulse(j) * j.axis));
  }
}

template <int N>
void solve_joints(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool use_bias) {
  JointSolver<N>& js = s.joints;
  for (JointConstraint<N>& j : js.slots) {
    if (!j.active) continue;
    if (!use_bias) place_joint(bodies, j);  // (the relax pass: the joint as the position update left it)
    const JointBodiesView<N> v = view(s, j);
    if (j.type == JointType::Point)
      solve_point(v, j, js.soft, use_bias, js.h);
    else
      solve_distance(v, j, js.soft, use_bias, js.h);
  }
}

template <int N>
Vec<N> joint_impulse(const JointConstraint<N>& j) {
  return j.type == JointType::Point ? j.linear_impulse : Vec<N>(axial_impulse(j) * j.axis);
}

#define WEDGE_INSTANTIATE(N)                                                                                    \
  template bool prepare_joints<N>(ContactState<N>&, const std::vector<Body<N>>&, const ContactSettings&, double); \
  template void warm_start_joints<N>(ContactState<N>&);                                                         \
  template void solve_joints<N>(ContactState<N>&, const std::vector<Body<N>>&, bool);                                                        \
  template Vec<N> joint_impulse<N>(const JointConstraint<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
