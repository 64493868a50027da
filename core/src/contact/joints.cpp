// Joints in the soft step (wedge/joint.hpp): each step derives every joint's effective masses from the
// bodies' poses at its start (prepare_joints); each sub-step places the joint (its lever arms and error
// from the poses now) as it applies its accumulated impulses (warm start), and solves it before the
// contacts in the solve and the relax pass (solve_joints), as Box2D v3 does.
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
//   Prismatic joint: the point rows across the axis n (turning with body a, so a's lever arm reaches
//                   anchor b): (Q K Q + n n^T) j = -Q (u + bias_rate C), Q = 1 - n n^T; the axis' own row
//                   carries the motor and the limits; the weld's angular rows hold the orientation.
// In the solve pass the error is corrected at the joint spring's rate (ContactSettings::joint_hertz and
// joint_damping_ratio, wedge/softness.hpp; the angular rows and a revolute joint's angle limits at
// joint_angular_hertz); the relax pass solves the velocity rows alone (no bias, full
// mass), so the correction leaves no velocity behind.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact/contact_system.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/ga/exp_log.hpp"
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

template <int N>
bool holds_orientation(const JointConstraint<N>& j) {
  return j.type == JointType::Revolute || j.type == JointType::Prismatic || j.type == JointType::Weld;
}

// Whether the joint has angular rows to solve: the weld's and the prismatic's k, the revolute's k - 1 off
// its plane (none in 2D, where the one plane is the revolute's own: it is a point joint and its angle).
template <int N>
bool has_turn_rows(const JointConstraint<N>& j) {
  return holds_orientation(j) && (N > 2 || j.type != JointType::Revolute);
}
// Whether a revolute joint's own row along its plane acts (a motor or limits).
template <int N>
bool has_plane_row(const JointConstraint<N>& j) {
  return j.type == JointType::Revolute && (j.motor || j.limit);
}

template <int N>
Rotor<N> rotor_a(const std::vector<Body<N>>& bodies, const JointConstraint<N>& j) {
  return j.a >= 0 ? bodies[j.a].rotor : Rotor<N>::identity();
}

// A revolute joint's angle now: u_b's turn from u_a toward v_a, less its value when the joint was added,
// taken the nearer way round from the angle at the last placing (so it may pass pi).
template <int N>
double revolute_angle(const Rotor<N>& ra, const Rotor<N>& rb, const JointConstraint<N>& j) {
  const Vec<N> ua = rotate(ra, j.u_a), va = rotate(ra, j.v_a), ub = rotate(rb, j.u_b);
  const double raw = std::atan2(ub.dot(va), ub.dot(ua)) - j.angle_offset;
  // The change since the last placing, into (-pi, pi] (remainder, exactly, is only needed past pi).
  const double change = raw - j.angle;
  return j.angle + (std::abs(change) <= std::numbers::pi ? change : std::remainder(change, 2.0 * std::numbers::pi));
}

// Whether placing the joint derives its frame from body a (place_orientation): a prismatic joint's axis
// always; a revolute joint's plane from 3D up (its rows need it) and its angle where the limits need it
// each sub-step (else the angle is taken once a step, prepare_joints).
template <int N>
bool places_frame(const JointConstraint<N>& j) {
  if (j.type == JointType::Prismatic) return true;
  return j.type == JointType::Revolute && (N > 2 || j.angle_each_substep);
}

// The frame a revolute or prismatic joint takes from body a (the revolute's plane and angle; the
// prismatic's axis), and with `with_turn` the orientation error: the turn (a bivector of angles, world)
// that would bring body b to where it belongs relative to a, -2 log(R_target ~R_b), R_target = R_a R_ref,
// the revolute's turned by its angle in the plane: R_target = exp(-angle p / 2) R_a R_ref.
template <int N>
void place_orientation(const std::vector<Body<N>>& bodies, JointConstraint<N>& j, bool with_turn) {
  const Rotor<N> ra = rotor_a(bodies, j);
  const Rotor<N>& rb = bodies[j.b].rotor;
  if (j.type == JointType::Prismatic) j.axis = rotate(ra, j.axis_local);
  if (j.type == JointType::Revolute) {
    j.plane = N == 2 ? j.plane_local : rotate(ra, j.plane_local);  // (a 2D rotation leaves the plane as it is)
    j.angle = revolute_angle(ra, rb, j);
  }
  if (!with_turn || !has_turn_rows(j)) return;
  Rotor<N> target = ra * j.reference;
  if (j.type == JointType::Revolute) target = exp<N>(j.plane * (-0.5 * j.angle)) * target;
  j.turn = log<N>(target * reverse(rb)) * -2.0;
}

// The lever arms and the error from the bodies' poses now (and a distance joint's axis; with
// `with_frame` the frame of a revolute or prismatic joint, and with `with_turn` the orientation error).
template <int N>
void place_joint(const std::vector<Body<N>>& bodies, JointConstraint<N>& j, bool with_frame, bool with_turn) {
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
  if (holds_orientation(j) && (with_frame || with_turn)) place_orientation(bodies, j, with_turn);
  if (j.type == JointType::Prismatic) {
    j.translation = j.axis.dot(j.separation);
    if (j.a >= 0) j.ra += j.separation;
    return;
  }
  if (j.type != JointType::Distance) return;
  j.distance = j.separation.norm();
  // (Anchors that meet leave the axis of the last sub-step, or the first axis if there was none.)
  if (j.distance > 1e-12) {
    j.axis = j.separation / j.distance;
  } else if (j.axis.squaredNorm() == 0.0) {
    j.axis = Vec<N>::UnitX();
  }
}

// The angular rows' effective mass. A turn impulse L (a bivector, on b; -L on a) changes the relative
// angular velocity w_b - w_a by M L, M = I_a^-1 + I_b^-1 (world, k x k). The weld and the prismatic
// joint hold all k rows: M^-1. The revolute holds the k - 1 rows off its plane p: with the projector P = 1 - p p^T it solves
// (P M P + p p^T) L = -P e, whose answer lies off p; its plane's own row (limits, motor) has the mass
// 1 / (p^T M p).
template <int N>
bool prepare_orientation(const JointBodiesView<N>& v, JointConstraint<N>& j) {
  BivMat<N> m = v.mb->inv_inertia;
  if (v.a) m += v.ma->inv_inertia;
  if (!has_turn_rows(j)) {  // (a 2D revolute joint: its plane's row only)
    const double along = j.plane.c.dot(m * j.plane.c);
    j.plane_mass = along > 0.0 ? 1.0 / along : 0.0;
    return !has_plane_row(j) || along > 0.0;
  }
  if (j.type == JointType::Revolute) {
    const Eigen::Matrix<double, kBiv<N>, 1> p = j.plane.c;
    const BivMat<N> off = BivMat<N>::Identity() - p * p.transpose();
    const double along = p.dot(m * p);
    if (!(along > 0.0)) return false;
    j.plane_mass = 1.0 / along;
    m = (off * m * off + p * p.transpose()).eval();
  }
  j.angular_mass = linalg::inverse<kBiv<N>>(m);
  return all_finite(j.angular_mass);
}

// The point rows' and the axis' effective masses, from the lever arms and the axis of the joint's last
// placing: each sub-step, as they turn with the bodies (a chain swinging fast strayed 9 cm at its pins
// with the masses of the step's start, 5 mm with these). False if the joint cannot act (K not
// invertible: neither body can move).
template <int N>
bool prepare_linear_rows(const JointBodiesView<N>& v, JointConstraint<N>& j) {
  const Mat<N> k = effective_mass_matrix(v, j);
  if (j.type == JointType::Prismatic) {
    const Mat<N> along = j.axis * j.axis.transpose(), across = Mat<N>::Identity() - along;
    const double axial = j.axis.dot(k * j.axis);
    if (!(axial > 0.0)) return false;
    j.axial_mass = 1.0 / axial;
    j.mass = linalg::inverse<N>(Mat<N>(across * k * across + along));
    j.linear_impulse = across * j.linear_impulse;  // (the axis turns with a: keep the warm start across it)
    return all_finite(j.mass) && std::isfinite(j.axial_mass);
  }
  if (j.type != JointType::Distance) {
    j.mass = linalg::inverse<N>(k);
    return all_finite(j.mass) && k.trace() > 0.0;
  }
  const double axial = j.axis.dot(k * j.axis);
  if (!(axial > 0.0)) return false;
  j.axial_mass = 1.0 / axial;
  return std::isfinite(j.axial_mass);
}

// At the step's first sub-step: the joint placed from the poses at the step's start, its spring, its
// angular rows' effective masses for the whole step (the bodies' world inertias are the step's: the
// solvers keep them through the sub-steps) and its linear rows'. False if the joint cannot act.
template <int N>
bool prepare_joint(ContactState<N>& s, const std::vector<Body<N>>& bodies, JointConstraint<N>& j, double h) {
  place_joint(bodies, j, true, true);
  if (j.spring) j.spring_soft = make_softness(j.frequency, j.damping_ratio, h);
  const JointBodiesView<N> v = view(s, j);
  if (holds_orientation(j) && !prepare_orientation(v, j)) return false;
  return prepare_linear_rows(v, j);
}

// How the anchors' separation bends away from a straight line in the sub-step: the second derivative of
// p_b - p_a, which for anchors turning with their bodies is (r_b . w_b) . w_b - (r_a . w_a) . w_a (d/dt
// of r is r . w). It is a small-turn term, quadratic in w: a body turning by more than kAheadTurn in a
// sub-step has its part held at that turn's value (scaled by (kAheadTurn / h|w|)^2), so that a body
// already spinning out of control is not driven faster by it (docs/joints.md, heavy loads).
constexpr double kAheadTurn = 0.25;  // rad per sub-step
template <int N>
Vec<N> turning_curvature(const Vec<N>& r, const Bivector<N>& w, double h) {
  const Vec<N> q = dot<N>(Vec<N>(dot<N>(r, w)), w);
  const double turn_squared = h * h * w.c.squaredNorm();  // (no square root on the hot path)
  return turn_squared > kAheadTurn * kAheadTurn ? Vec<N>(q * (kAheadTurn * kAheadTurn / turn_squared)) : q;
}
template <int N>
Vec<N> anchor_curvature(const JointBodiesView<N>& v, const JointConstraint<N>& j, double h) {
  Vec<N> q = turning_curvature(j.rb, v.b->w, h);
  if (v.a) q -= turning_curvature(j.ra, v.a->w, h);
  return q;
}

// A distance joint's row along its axis (a rod, or a spring): the impulse that brings the axial velocity
// plus `ahead` to -bias (softened), accumulated in `total`.
template <int N>
void solve_axial_row(const JointBodiesView<N>& v, JointConstraint<N>& j, double bias, const Softness& soft,
                     double& total, double ahead = 0.0) {
  const double u = j.axis.dot(relative_anchor_velocity(v, j)) + ahead;
  const double change = -soft.mass_scale * j.axial_mass * (u + bias) - soft.impulse_scale * total;
  total += change;
  apply(v, j, Vec<N>(change * j.axis));
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
  if (h > 0.0) u += (0.5 * h) * anchor_curvature(v, j, h);
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
double distance_curvature(const JointBodiesView<N>& v, const JointConstraint<N>& j, double h) {
  if (j.distance <= 1e-12) return 0.0;
  const Vec<N> u = relative_anchor_velocity(v, j);
  const double along = j.axis.dot(u);
  return std::max(u.squaredNorm() - along * along, 0.0) / j.distance + j.axis.dot(anchor_curvature(v, j, h));
}

// A limit's one-sided row (its accumulated impulse `total` stays >= 0), linear or angular: a limit still
// open by `gap` may close by it in the sub-step and no more (speculative, rigid); one already passed is
// pushed back softly in the solve pass. `speed`: the row's closing velocity now (toward the limit is
// negative), `mass`: its effective mass. Returns the change of `total`, to apply along the row.
inline double limit_row_change(double gap, double speed, double mass, double h, const Softness& soft, bool use_bias,
                               double& total) {
  double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
  if (gap > 0.0) {
    bias = gap / h;
  } else if (use_bias) {
    bias = soft.bias_rate * gap;
    mass_scale = soft.mass_scale;
    impulse_scale = soft.impulse_scale;
  }
  double change = -mass_scale * mass * (speed + bias) - impulse_scale * total;
  change = std::max(total + change, 0.0) - total;
  total += change;
  return change;
}

// A limit along the axis (limit_row_change), `sign` 1 for a lower limit, -1 for an upper one.
template <int N>
void solve_axial_limit(const JointBodiesView<N>& v, JointConstraint<N>& j, double gap, double sign, double& total,
                       const Softness& soft, bool use_bias, double h, double ahead) {
  const double speed = sign * (j.axis.dot(relative_anchor_velocity(v, j)) + ahead);
  const double change = limit_row_change(gap, speed, j.axial_mass, h, soft, use_bias, total);
  apply(v, j, Vec<N>(sign * change * j.axis));
}

template <int N>
void solve_distance(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft, bool use_bias,
                    double h) {
  const Softness rigid{};
  const Softness& correction = use_bias ? soft : rigid;
  const double ahead = use_bias ? 0.5 * h * distance_curvature(v, j, h) : 0.0;
  if (!j.spring || j.min_length >= j.max_length) {
    const double length = j.spring ? j.min_length : j.length;
    const double bias = use_bias ? soft.bias_rate * (j.distance - length) : 0.0;
    solve_axial_row(v, j, bias, correction, j.impulse, ahead);
    return;
  }
  if (j.frequency > 0.0)  // (the spring is physics, not a correction: both passes)
    solve_axial_row(v, j, j.spring_soft.bias_rate * (j.distance - j.length), j.spring_soft, j.impulse);
  if (j.min_length > 0.0) solve_axial_limit(v, j, j.distance - j.min_length, 1.0, j.lower_impulse, soft, use_bias, h, ahead);
  if (std::isfinite(j.max_length))
    solve_axial_limit(v, j, j.max_length - j.distance, -1.0, j.upper_impulse, soft, use_bias, h, ahead);
}

template <int N>
using BivColumn = Eigen::Matrix<double, kBiv<N>, 1>;

template <int N>
BivColumn<N> relative_angular_velocity(const JointBodiesView<N>& v) {
  BivColumn<N> w = v.b->w.c;
  if (v.a) w -= v.a->w.c;
  return w;
}

// A turn impulse L on b and -L on a.
template <int N>
void apply_turn(const JointBodiesView<N>& v, const BivColumn<N>& l) {
  v.b->w.c += inverse_inertia_times(*v.mb, l);
  if (v.a) v.a->w.c -= inverse_inertia_times(*v.ma, l);
}

// The revolute's own row along its plane: the motor (toward motor_speed, at most max_motor_torque), then
// the angle limits (one-sided; speculative while inside them, softly pushed back once past).
template <int N>
void solve_plane_row(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& turn_soft, bool use_bias,
                     double h) {
  const BivColumn<N> p = j.plane.c;
  if (j.motor) {
    const double w = p.dot(relative_angular_velocity(v));
    const double most = j.max_motor_torque * h, old = j.motor_impulse;
    j.motor_impulse = std::clamp(old - j.plane_mass * (w - j.motor_speed), -most, most);
    apply_turn(v, BivColumn<N>((j.motor_impulse - old) * p));
  }
  if (!j.limit) return;
  const auto limit = [&](double gap, double sign, double& total) {
    const double speed = sign * p.dot(relative_angular_velocity(v));
    const double change = limit_row_change(gap, speed, j.plane_mass, h, turn_soft, use_bias, total);
    apply_turn(v, BivColumn<N>(sign * change * p));
  };
  limit(j.angle - j.lower_angle, 1.0, j.lower_angle_impulse);
  limit(j.upper_angle - j.angle, -1.0, j.upper_angle_impulse);
}

// The rows that hold the relative orientation (the weld's k, the revolute's k - 1 off its plane): the
// relative angular velocity brought to the error's correction, softly (prepare_orientation's masses).
template <int N>
void solve_orientation(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft, bool use_bias) {
  BivColumn<N> e = relative_angular_velocity(v);
  if (use_bias) e -= soft.bias_rate * j.turn.c;
  const BivColumn<N> p = j.plane.c;
  const bool revolute = j.type == JointType::Revolute;
  if (revolute) e -= p * p.dot(e);
  const double mass_scale = use_bias ? soft.mass_scale : 1.0, impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  BivColumn<N> l = -mass_scale * (j.angular_mass * e) - impulse_scale * j.angular_impulse.c;
  if (revolute) l -= p * p.dot(l);  // (round-off: the rows act off the plane only)
  j.angular_impulse.c += l;
  apply_turn(v, l);
}

// A prismatic joint: its angular rows (all k), the motor and the limits along its axis, then the point
// rows across it, which aim, as solve_point's do, at the end of the sub-step.
template <int N>
void solve_prismatic(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft,
                     const Softness& turn_soft, bool use_bias, double h) {
  solve_orientation(v, j, turn_soft, use_bias);
  if (j.motor) {
    const double u = j.axis.dot(relative_anchor_velocity(v, j));
    const double most = j.max_motor_force * h, old = j.motor_impulse;
    j.motor_impulse = std::clamp(old - j.axial_mass * (u - j.motor_speed), -most, most);
    apply(v, j, Vec<N>((j.motor_impulse - old) * j.axis));
  }
  if (j.limit) {
    solve_axial_limit(v, j, j.translation - j.lower_translation, 1.0, j.lower_impulse, soft, use_bias, h, 0.0);
    solve_axial_limit(v, j, j.upper_translation - j.translation, -1.0, j.upper_impulse, soft, use_bias, h, 0.0);
  }
  Vec<N> e = relative_anchor_velocity(v, j);
  if (use_bias) e += (0.5 * h) * anchor_curvature(v, j, h) + soft.bias_rate * j.separation;
  e -= j.axis * j.axis.dot(e);
  const double mass_scale = use_bias ? soft.mass_scale : 1.0, impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  Vec<N> change = -mass_scale * (j.mass * e) - impulse_scale * j.linear_impulse;
  change -= j.axis * j.axis.dot(change);  // (round-off: the rows act across the axis only)
  j.linear_impulse += change;
  apply(v, j, change);
}

// A revolute or weld joint: its angular rows, then its point rows. A soft weld is a spring in both
// passes (its own frequency), as a distance joint's spring is.
template <int N>
void solve_angular_joint(const JointBodiesView<N>& v, JointConstraint<N>& j, const Softness& soft,
                         const Softness& turn_soft, bool use_bias, double h) {
  if (has_plane_row(j)) solve_plane_row(v, j, turn_soft, use_bias, h);
  const double ahead = use_bias ? h : 0.0;
  if (!has_turn_rows(j)) {  // (a 2D revolute joint)
    solve_point(v, j, soft, use_bias, ahead);
    return;
  }
  if (j.spring) {
    solve_orientation(v, j, j.spring_soft, true);
    solve_point(v, j, j.spring_soft, true, ahead);
    return;
  }
  solve_orientation(v, j, turn_soft, use_bias);
  solve_point(v, j, soft, use_bias, ahead);
}

// The accumulated turn impulse on b (N m s, world): the rows off the plane, the motor and the limits.
template <int N>
BivColumn<N> turn_impulse(const JointConstraint<N>& j) {
  if (j.type != JointType::Revolute) return j.angular_impulse.c;
  return j.angular_impulse.c + (j.motor_impulse + j.lower_angle_impulse - j.upper_angle_impulse) * j.plane.c;
}


// A revolute joint's angle is taken each sub-step where its limits need it, or where it turns so fast
// (beyond kSubstepAngleTurn in a step, now or at its motor's speed) that once a step might not tell which
// way round it went.
constexpr double kSubstepAngleTurn = 1.0;  // rad per step
template <int N>
bool angle_each_substep(const JointBodiesView<N>& v, const JointConstraint<N>& j, double step) {
  const double spin = std::max(std::abs(j.plane.c.dot(relative_angular_velocity(v))),
                               j.motor ? std::abs(j.motor_speed) : 0.0);
  return j.limit || spin * step > kSubstepAngleTurn;
}

}  // namespace

template <int N>
bool prepare_joints(ContactState<N>& s, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                    double h) {
  JointSolver<N>& js = s.joints;
  if (s.soft.substep > 0) return js.any_active;  // (prepared at the step's first sub-step)
  js.any_active = false;
  if (js.slots.empty()) return false;
  js.h = h;
  js.soft = make_softness(std::min(settings.joint_hertz, 0.25 / h), settings.joint_damping_ratio, h);
  js.turn_soft = make_softness(std::min(settings.joint_angular_hertz, 0.25 / h), settings.joint_damping_ratio, h);
  const double step = h * settings.substeps;
  for (JointConstraint<N>& j : js.slots) {
    j.active = j.live && (moves(s, bodies, j.b) || (j.a >= 0 && moves(s, bodies, j.a)));
    if (!j.active) continue;
    j.active = prepare_joint(s, bodies, j, h);
    if (j.type == JointType::Revolute) j.angle_each_substep = angle_each_substep(view(s, j), j, step);
    js.any_active = js.any_active || j.active;
  }
  return js.any_active;
}

// Each joint in slot order, `one(j)` for each active one: in 2D with every call it makes inlined into the
// loop (flatten: the 2D rows' arithmetic is a few dozen operations, less than calling it), above 2D as
// the compiler's own inlining decides.
template <int N, class One>
void for_each_active_joint(JointSolver<N>& js, const One& one) {
  for (JointConstraint<N>& j : js.slots) {
    if (!j.active) continue;
    if constexpr (N == 2)
      [&]() __attribute__((flatten)) { one(j); }();
    else
      one(j);
  }
}

template <int N>
void warm_start_joints(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  for_each_active_joint(s.joints, [&](JointConstraint<N>& j) {
    const JointBodiesView<N> v = view(s, j);
    if (s.soft.substep > 0) {  // (the first sub-step's placing is prepare_joints')
      place_joint(bodies, j, places_frame(j), has_turn_rows(j));
      prepare_linear_rows(v, j);
    }
    apply(v, j, joint_impulse(j));
    if (has_turn_rows(j) || has_plane_row(j)) apply_turn(v, turn_impulse(j));
  });
}

template <int N>
void solve_joints(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool use_bias) {
  JointSolver<N>& js = s.joints;
  for_each_active_joint(js, [&](JointConstraint<N>& j) {
    // (the relax pass: the joint as the position update left it; the orientation error only for a soft
    // weld, whose spring acts in both passes)
    if (!use_bias) place_joint(bodies, j, places_frame(j), j.spring);
    const JointBodiesView<N> v = view(s, j);
    switch (j.type) {
      case JointType::Point:
        solve_point(v, j, js.soft, use_bias, use_bias ? js.h : 0.0);
        break;
      case JointType::Distance:
        solve_distance(v, j, js.soft, use_bias, js.h);
        break;
      case JointType::Prismatic:
        solve_prismatic(v, j, js.soft, js.turn_soft, use_bias, js.h);
        break;
      case JointType::Revolute:
      case JointType::Weld:
        solve_angular_joint(v, j, js.soft, js.turn_soft, use_bias, js.h);
        break;
    }
  });
}

template <int N>
double joint_angle_now(const JointConstraint<N>& j, const std::vector<Body<N>>& bodies) {
  return revolute_angle(rotor_a(bodies, j), bodies[j.b].rotor, j);
}

template <int N>
Vec<N> joint_impulse(const JointConstraint<N>& j) {
  if (j.type == JointType::Distance) return axial_impulse(j) * j.axis;
  if (j.type == JointType::Prismatic)
    return j.linear_impulse + (j.motor_impulse + j.lower_impulse - j.upper_impulse) * j.axis;
  return j.linear_impulse;
}

template <int N>
Bivector<N> joint_turn_impulse(const JointConstraint<N>& j) {
  Bivector<N> l;
  if (holds_orientation(j)) l.c = turn_impulse(j);
  return l;
}

#define WEDGE_INSTANTIATE(N)                                                                                    \
  template bool prepare_joints<N>(ContactState<N>&, const std::vector<Body<N>>&, const ContactSettings&, double); \
  template void warm_start_joints<N>(ContactState<N>&, const std::vector<Body<N>>&);                          \
  template double joint_angle_now<N>(const JointConstraint<N>&, const std::vector<Body<N>>&);                  \
  template void solve_joints<N>(ContactState<N>&, const std::vector<Body<N>>&, bool);                                                        \
  template Vec<N> joint_impulse<N>(const JointConstraint<N>&);                                                  \
  template Bivector<N> joint_turn_impulse<N>(const JointConstraint<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
