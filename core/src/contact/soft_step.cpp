// The soft step (Catto, "Solver2D" 2024 and Box2D v3): each step is taken as sub-steps, and in each
//   integrate_velocities   gravity and forces (World)
//   solve (use_bias)       grabs, then contacts: soft normal constraints that push penetration out at
//                          a spring's rate, friction in the Coulomb cone; warm started
//   integrate_positions    (World)
//   relax                  the same passes without the push, so the push leaves no velocity behind
// and once after the last sub-step restitution, from the approach speeds the step began with.
//
// Contacts are found once per step. Within it each point keeps its normal, its lever arms (the
// Jacobian) and its effective masses; what changes is its separation, computed from how far the two
// bodies have moved and turned since the step began: s = base + n . (dp_b + dq_b r_b - dp_a - dq_a r_a).
// A point still apart (s > 0) may close by s in the sub-step and no more (speculative contact); a
// penetrating one is pushed out by a soft constraint of frequency contact_hertz and damping ratio
// contact_damping_ratio, never faster than contact_push_speed. The soft constraint is implicit Euler on
// a damped spring, as in grabs (wedge/grab.hpp): mass_scale and impulse_scale blend the rigid answer
// with the accumulated impulse so the push is the same for light and heavy bodies.
//
// Why this holds stacks: a sub-step of h/4 leaves a quarter of the velocity error for the same passes,
// and the relax pass removes the push's velocity, so a stack is not thrown up by its own correction;
// the warm-started impulses of the last sub-step carry the load from one sub-step to the next.
#include <algorithm>
#include <cmath>

#include "contact/impulses.hpp"
#include "instantiate.hpp"

namespace wedge::contact {

namespace {

// Implicit spring coefficients (as b2MakeSoft): bias rate 1/s, and the mass and impulse scales.
struct Softness {
  double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
};
Softness make_soft(double hertz, double zeta, double h) {
  if (hertz <= 0.0) return {0.0, 1.0, 0.0};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

// An impulse of `change` along the normal at the point (apply_impulse through the normal's rows).
template <int N>
void apply_normal_impulse(SolverBody<N>& a, SolverBody<N>& b, const PointConstraint<N>& p, const Vec<N>& n,
                          double change) {
  if (!a.frozen) {
    a.v -= (a.inv_mass * change) * n;
    a.w.c -= change * p.dn_a;
  }
  if (!b.frozen) {
    b.v += (b.inv_mass * change) * n;
    b.w.c += change * p.dn_b;
  }
}

// Applies every point's accumulated impulse (the last sub-step's answer) to the fresh velocities.
template <int N>
void warm_start_substep(ContactState<N>& s) {
  const auto apply = [&](const Constraint<N>& c, int k) {
    s.points[c.first + k].normal_total += s.points[c.first + k].normal_impulse;
    apply_accumulated_point(s, c, k);
  };
  for_each_constraint_in_pairs(
      s, [&](const Constraint<N>& c) { for (int k = 0; k < c.count; ++k) apply(c, k); },
      [&](const Constraint<N>& c, const Constraint<N>& d) { points_in_turn(c, d, apply); });
}

// One pass over the contacts: per constraint the normal impulses first (soft when use_bias and
// penetrating), then friction in the cone of the updated normal impulse.
template <int N>
struct ContactPass {
  ContactState<N>& s;
  double inv_h, push_speed;
  bool use_bias;

  void normal(const Constraint<N>& c, int k) const {
    SolverBody<N>& a = s.solver_bodies[c.a];
    SolverBody<N>& b = s.solver_bodies[c.b];
    const Vec<N>& n = c.normal;
    PointConstraint<N>& p = s.points[c.first + k];
    const double sep = p.separation;
    double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (sep > 0.0) {
      bias = sep * inv_h;  // speculative: may close the gap within the sub-step, no more
    } else if (use_bias) {
      bias = std::max(s.soft_mass_scale * s.soft_bias_rate * sep, -push_speed);
      mass_scale = s.soft_mass_scale;
      impulse_scale = s.soft_impulse_scale;
    }
    const double un = n.dot(b.v - a.v) + p.jn_b.dot(b.w.c) - p.jn_a.dot(a.w.c);
    const double next =
        std::max(p.normal_impulse - p.normal_mass * (mass_scale * un + bias) - impulse_scale * p.normal_impulse, 0.0);
    const double change = next - p.normal_impulse;
    p.normal_impulse = next;
    p.normal_total += change;
    apply_normal_impulse(a, b, p, n, change);
  }

  void friction(const Constraint<N>& c, int k) const {
    PointConstraint<N>& p = s.points[c.first + k];
    if (!(p.friction > 0.0) || (p.normal_impulse <= 0.0 && p.tangent_impulse.isZero(0.0))) return;
    SolverBody<N>& a = s.solver_bodies[c.a];
    SolverBody<N>& b = s.solver_bodies[c.b];
    const Vec<N>& n = c.normal;
    const Vec<N> u = relative_velocity(a, b, p);
    const Vec<N> next = friction_update(p, n, Vec<N>(u - n.dot(u) * n));
    const Vec<N> change = next - p.tangent_impulse;
    p.tangent_impulse = next;
    apply_impulse(a, b, p, change);
  }

  void one(const Constraint<N>& c) const {
    for (int k = 0; k < c.count; ++k) normal(c, k);
    for (int k = 0; k < c.count; ++k) friction(c, k);
  }
  // Two constraints of one colour in turn (for_each_constraint_in_pairs).
  void two(const Constraint<N>& c, const Constraint<N>& d) const {
    points_in_turn(c, d, [this](const Constraint<N>& e, int k) { normal(e, k); });
    points_in_turn(c, d, [this](const Constraint<N>& e, int k) { friction(e, k); });
  }
};

template <int N>
void solve_contacts(ContactState<N>& s, const ContactSettings& settings, double h, bool use_bias) {
  const ContactPass<N> pass{s, 1.0 / h, settings.contact_push_speed, use_bias};
  for_each_constraint_in_pairs(
      s, [&](const Constraint<N>& c) { pass.one(c); },
      [&](const Constraint<N>& c, const Constraint<N>& d) { pass.two(c, d); });
}

// Restitution once the sub-steps are done: points that approached faster than the threshold when the
// step began and took an impulse get the normal velocity -e u_n (Box2D v3's rule).
template <int N>
void apply_restitution(ContactState<N>& s, const ContactSettings& settings) {
  for_each_constraint_by_colour(s, [&](const Constraint<N>& c) {
    if (c.restitution <= 0.0) return;
    SolverBody<N>& a = s.solver_bodies[c.a];
    SolverBody<N>& b = s.solver_bodies[c.b];
    for (int k = c.first; k < c.first + c.count; ++k) {
      PointConstraint<N>& p = s.points[k];
      if (p.approach > -settings.restitution_threshold || p.normal_total <= 0.0) continue;
      const double un = c.normal.dot(b.v - a.v) + p.jn_b.dot(b.w.c) - p.jn_a.dot(a.w.c);
      const double next = std::max(p.normal_impulse - p.normal_mass * (un + c.restitution * p.approach), 0.0);
      const double change = next - p.normal_impulse;
      p.normal_impulse = next;
      p.normal_total += change;
      apply_normal_impulse(a, b, p, c.normal, change);
    }
  });
}

// m^T v: Eigen's sums for its coefficients, stored in pairs (ga::detail::store_pairs) since the dot
// products below read it as packets (a stalled store forward cost a quarter of this stage in 2D).
template <int N>
Vec<N> transpose_times(const Mat<N>& m, const Vec<N>& v) {
  double t[N];
  for (int i = 0; i < N; ++i) t[i] = m.col(i).dot(v);
  Vec<N> o;
  ga::detail::store_pairs<N>(t, o.data());
  return o;
}

}  // namespace

template <int N>
void prepare_soft_step(ContactState<N>& s, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                       double h) {
  for_each_body(s, int(bodies.size()), [&](int i) {
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.x0 = bodies[i].center;
    sb.r0_inverse = to_matrix(bodies[i].rotor).transpose();
    sb.dp.setZero();
    sb.dq.setIdentity();
    // Bodies that do not move are only read: writing their unchanged velocities would chain every
    // contact with the ground through one memory location (and two workers through one cache line).
    sb.frozen = !moves(s, bodies, i);
  });
  // One spring for every contact. (Box2D v3 doubles it against static bodies; with the 8 or 16 points
  // of a 3D or 4D face that made a light box under a heavy one chatter at 0.4-0.8 m/s.)
  const Softness soft = make_soft(std::min(settings.contact_hertz, 0.125 / h), settings.contact_damping_ratio, h);
  s.soft_bias_rate = soft.bias_rate;
  s.soft_mass_scale = soft.mass_scale;
  s.soft_impulse_scale = soft.impulse_scale;
  for_each_constraint(s, [&](const Constraint<N>& c) {
    for (int k = c.first; k < c.first + c.count; ++k) {
      PointConstraint<N>& p = s.points[k];
      p.base_separation = p.gap - c.normal.dot(p.rb - p.ra);
      p.separation = p.gap;
      p.normal_impulse = settings.warm_start ? p.warm_normal : 0.0;
      p.tangent_impulse = settings.warm_start ? p.warm_tangent : Vec<N>::Zero();
      p.normal_total = 0.0;
    }
  });
}

template <int N>
void solve_substep(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h,
                   bool use_bias) {
  bool grabs = false;
  if (use_bias) {
    grabs = prepare_grabs(s, bodies, h);
    if (s.constraints.empty() && !grabs) return;
    load_velocities(s, bodies);
    if (grabs) warm_start_grabs(s);
    warm_start_substep(s);
  } else {
    grabs = !s.driven.empty();
    if (s.constraints.empty() && !grabs) return;
  }
  if (grabs) solve_grabs(s);
  solve_contacts(s, settings, h, use_bias);
  store_velocities(s, bodies);
}

template <int N>
void track_substep_motion(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  if (s.constraints.empty()) return;
  for_each_body(s, int(bodies.size()), [&](int i) {
    if (bodies[i].type == BodyType::Static || !s.awake[i]) return;
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.dp = bodies[i].center - sb.x0;
    sb.dq = to_matrix(bodies[i].rotor) * sb.r0_inverse;
  });
  // s = base + n . (dp_b - dp_a) + (dq_b^T n) . rb - (dq_a^T n) . ra: the turned normal once per pair.
  for_each_constraint(s, [&](const Constraint<N>& c) {
    const SolverBody<N>& a = s.solver_bodies[c.a];
    const SolverBody<N>& b = s.solver_bodies[c.b];
    const double moved = c.normal.dot(b.dp - a.dp);
    const Vec<N> na = transpose_times(a.dq, c.normal), nb = transpose_times(b.dq, c.normal);
    for (int k = c.first; k < c.first + c.count; ++k) {
      PointConstraint<N>& p = s.points[k];
      p.separation = p.base_separation + moved + nb.dot(p.rb) - na.dot(p.ra);
    }
  });
}

template <int N>
void finish_soft_step(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings) {
  if (s.constraints.empty()) return;
  load_velocities(s, bodies);
  apply_restitution(s, settings);
  keep_for_warm_start(s);
  store_velocities(s, bodies);
}

#define WEDGE_INSTANTIATE(N)                                                                                   \
  template void prepare_soft_step<N>(ContactState<N>&, const std::vector<Body<N>>&, const ContactSettings&, double); \
  template void solve_substep<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double, bool); \
  template void track_substep_motion<N>(ContactState<N>&, const std::vector<Body<N>>&);                       \
  template void finish_soft_step<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
