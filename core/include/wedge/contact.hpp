// Contact response (paper section 6, after Guendelman, Bridson & Fedkiw 2003): materials and how a pair
// combines them, the settings of the contact stages of World::step, and what a step reports about its
// contacts afterwards (arrays, in a fixed order; never callbacks during the step).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "wedge/collision/manifold.hpp"

namespace wedge {

struct BodyId {
  std::uint32_t index = 0;
  friend bool operator==(BodyId a, BodyId b) { return a.index == b.index; }
};

// Per body. A pair combines them as Box2D does: the geometric mean of the friction coefficients and the
// larger restitution.
struct Material {
  double restitution = 0.0;       // [0, 1]: ratio of normal separating to approaching speed
  double friction = 0.5;          // static (Coulomb) coefficient, >= 0: sticks while |j_t| <= mu_s j_n
  double kinetic_friction = 0.4;  // >= 0: sliding friction |j_t| = mu_k j_n
};
// (Equal coefficients, the usual case, give the coefficient itself: sqrt(a a) rounds to a wherever a a
// neither underflows nor overflows, so the square root is skipped there, to the bit.)
inline double mix_friction(double a, double b) {
  if (a == b && a > 0x1p-500 && a < 0x1p500) return a;
  return std::sqrt(a * b);
}
inline double mix_restitution(double a, double b) { return std::max(a, b); }

// Which contact solver World::step runs.
//   SoftStep: Box2D v3's soft step (Catto 2024), sub-stepped with soft contacts and a relax pass, and
//             restitution applied once at the end (docs/contact.md). Tall stacks and large mass ratios.
//   Paper:    the paper's section 6 (Guendelman et al. 2003): collision processing on predicted
//             positions, contact processing, shock propagation and split-impulse position correction.
enum class ContactSolver { SoftStep, Paper };

// The contact stages of the step. Each field says its unit; the defaults suit bodies of about 0.1-10 m
// at 60-1000 Hz.
struct ContactSettings {
  ContactSolver solver = ContactSolver::SoftStep;
  // SoftStep: each step is taken as this many sub-steps, each a velocity update, one solve pass with the
  // soft contacts (warm started), the position update, and one relax pass without the contacts' push.
  int substeps = 8;
  // Hz: the soft contacts' natural frequency, capped at an eighth of the sub-step rate (60 Hz for 8
  // sub-steps of a 60 Hz step); damping ratio 10 (over-damped). A contact is a spring of stiffness
  // m_eff (2 pi f)^2, m_eff the point's normal effective mass: a stack sags by its load over that
  // stiffness, so the sag falls with f^2, and f may rise with the sub-step rate (docs/contact.md).
  double contact_hertz = 60.0;
  double contact_damping_ratio = 10.0;
  // Hz and damping ratio: the soft constraint that corrects a joint's position error (wedge/joint.hpp),
  // its frequency capped at a quarter of the sub-step rate (120 Hz for 8 sub-steps of a 60 Hz step;
  // above it a chain's single pass per sub-step diverges). Like a contact, a joint is then a stiff spring:
  // held still it stretches by its load over m_eff (2 pi f)^2 (m_eff its effective mass along the load),
  // 0.035 mm per link's weight between two equal links at 120 Hz (docs/joints.md).
  double joint_hertz = 120.0;
  double joint_damping_ratio = 2.0;
  // Hz: the same for the rows that hold a joint's relative orientation (a revolute joint's off its plane,
  // a weld's, a prismatic joint's), capped likewise: 240 Hz for 8 sub-steps of a 120 Hz step, 120 Hz for
  // 8 of a 60 Hz step. Stiffer than joint_hertz by default, since a turn off a revolute joint's plane is
  // what a knock shows first: the solve pass takes 90% of a knock's turning off the plane out in the
  // sub-step it arrives at 240 Hz (960 sub-steps a second), 79% at 120 Hz (docs/joints.md).
  double joint_angular_hertz = 240.0;
  // m/s: the fastest a soft contact pushes penetrating bodies apart.
  double contact_push_speed = 3.0;
  // m/s: SoftStep applies restitution to points that approached faster than this when the step began.
  double restitution_threshold = 1.0;
  // Contact recycling: a pair of flat-faced shapes keeps its contact points (attached to the bodies, the
  // normal fixed) while their relative motion since the points were found moves no point of them by
  // more than recycle_distance (m) and neither body has turned by more than recycle_angle (rad); only
  // the separations are updated. It holds tall stacks (docs/contact.md). 0 turns it off.
  double recycle_distance = 0.05;
  double recycle_angle = 0.2;
  // Both solvers: contact_margin, face_preference, static_slip_speed, warm_start and the sleep settings.
  // The paper's solver only: collision_iterations, contact_iterations, contact_tolerance, the shock
  // settings, linear_slop, position_correction and position_iterations.
  // m. The narrow phase also reports points up to this far apart, so a contact that closes during the
  // step is processed before it penetrates ("predicted positions", first order in h).
  double contact_margin = 0.02;
  // m: CollisionSettings::face_preference for the step's narrow phase (stable face-to-face manifolds).
  double face_preference = 0.002;
  // m/s. A contact point slipping slower than this when the step begins holds with the static friction
  // coefficient, a faster one slides with the kinetic one.
  // (1 cm/s: the residual slip sequential impulses leave in a 20-row pyramid at 60 Hz is below it.)
  double static_slip_speed = 0.01;
  // Collision processing (before the velocity update): passes over the closing contacts with the
  // pair's restitution.
  int collision_iterations = 5;
  // Contact processing (after the velocity update): passes with restitution 0, starting from the
  // impulses the same features received in the last step (warm start) unless turned off.
  int contact_iterations = 10;
  bool warm_start = true;
  // m/s. Contact processing stops early once a pass changes no point's velocity by more than this,
  // along the normal or (through friction) in the tangent plane: a warm-started resting stack is often
  // converged after one or two passes. Kept as small as shock_tolerance, for the same reason. 0 always
  // runs contact_iterations passes.
  double contact_tolerance = 1e-6;
  // Then shock propagation: the contact graph's levels upward from static bodies, each level solved with
  // the levels below it frozen (infinite mass), at most this many passes per level; 0 turns it off.
  int shock_iterations = 20;
  // m/s. A level stops early once a pass changes no point's normal velocity by more than this. The
  // residual it leaves acts every step in the same direction, so it is kept far below what a resting
  // stack may drift: 1e-6 m/s is 0.06 mm a minute (a 4D tower of 10 tesseracts at 120 Hz stays within
  // 0.3 mm for 60 s; 1e-4 lets it creep by millimetres). 0 turns this off; a level still stops once
  // its passes stall (solver.cpp, shock_propagation).
  double shock_tolerance = 1e-6;
  // m. Penetration below this is left alone; deeper penetration is pushed out by split impulses, which
  // move positions without adding kinetic energy.
  double linear_slop = 0.0005;
  // Fraction (0, 1] of the penetration beyond the slop removed per step.
  double position_correction = 0.2;
  int position_iterations = 4;
  // Continuous collision against static bodies (contact/continuous.cpp): a dynamic body whose points may
  // have moved more than half its inradius in the step is swept from its pose at the step's start to
  // its pose at the end against the static shapes on its way (time of impact, collision/time_of_impact).
  // If it reached one and the contacts let it through (it ends beyond the wall, or in it deeper than
  // continuous_gap), it is put back at the time of impact, continuous_gap short of the wall, and
  // collides there; the next step's contacts take it from there. A shape it already touched at the
  // start is left to the contacts. Off: fast bodies rely on the speculative margin alone, which lets a
  // thin plate spinning at 100 rad/s pass through a 1 cm wall.
  bool continuous = true;
  double continuous_gap = 0.005;  // m
  // rad: the most a body may turn in one step; faster spins are scaled down to it after the solver
  // (377 rad/s at 120 Hz). The sub-steps' rotation and gyroscopic term gain energy beyond a few radians
  // per step, which a thin rod struck off its axis can reach (contact/continuous.cpp, limit_spin).
  double max_turn = 3.141592653589793;
  // Sleeping: an island whose bodies all move slower than these for time_to_sleep stops being simulated
  // until something touches it or input is applied to one of its bodies. With allow_sleep off no island
  // is formed and the rest timers stay at zero: turned on, a resting island sleeps time_to_sleep later.
  bool allow_sleep = true;
  double sleep_linear_speed = 0.02;   // m/s, of the centre and of the bounding-sphere rim (|w| r)
  double time_to_sleep = 0.5;         // s
};

// A pair that began touching in the last step: some point received a normal impulse or penetrates.
// Sorted by (a, b); a < b in creation order, and the normal points from a to b.
template <int N>
struct ContactBeginEvent {
  BodyId a, b;
  Vec<N> point = Vec<N>::Zero();   // m, world: the contact points weighted by their normal impulses
  Vec<N> normal = Vec<N>::Zero();  // unit
  double normal_impulse = 0.0;     // N s, total over the manifold in this step (collision and contact)
  double approach_speed = 0.0;     // m/s, closing normal speed at the start of the step (>= 0)
};

// A pair that stopped touching in the last step; sorted by (a, b).
struct ContactEndEvent {
  BodyId a, b;
};

// A contact as the last step left it (for tools and tests): the manifold at the start of the step and
// the normal impulse each point received in it.
template <int N>
struct ContactInfo {
  BodyId a, b;
  Manifold<N> manifold;
  std::array<double, kMaxManifoldPoints<N>> normal_impulse{};  // N s
  bool touching = false;
};

}  // namespace wedge
