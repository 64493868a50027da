// Collision and contact processing (paper section 6, after Guendelman, Bridson & Fedkiw 2003), as
// sequential impulses on the step's constraints. Each point solves its full n x n block: the impulse
// that stops the relative velocity (static friction) is kept when it lies inside the friction cone;
// otherwise the point slides, with the tangential impulse mu_k times the normal one and the normal part
// re-solved with it. Impulses accumulate per stage and are clamped to push, never pull.
//
// Predicted positions: a point with gap g (m) and normal velocity u_n is where the bodies will be after
// the step to first order, g + h u_n. Collision processing (before the velocity update) acts on points
// that close within the step, giving them the separating speed -e u_n. Contact processing (after it)
// allows every point to close its gap exactly, u_n >= -max(g, 0)/h, and no more.
#include <algorithm>
#include <Eigen/LU>

#include "contact/contact_system.hpp"

namespace wedge::contact {

namespace {

template <int N>
void apply_impulse(SolverBody<N>& a, SolverBody<N>& b, const PointConstraint<N>& p, const Vec<N>& j) {
  if (!a.frozen) {
    a.v -= a.inv_mass * j;
    a.w.c -= p.wa * j;
  }
  if (!b.frozen) {
    b.v += b.inv_mass * j;
    b.w.c += p.wb * j;
  }
}

// One point: the accumulated impulse moves so that the relative velocity becomes target * n with no
// slip, then is projected: no pull, and a kinetic slide outside the static friction cone.
template <int N>
void solve_point(SolverBody<N>& a, SolverBody<N>& b, PointConstraint<N>& p, const Constraint<N>& c, double target) {
  const Vec<N>& n = c.normal;
  const Vec<N> u = relative_velocity(a, b, p);
  const Vec<N> old = p.impulse;
  Vec<N> next = old + p.k_inv * (target * n - u);
  const double pn = next.dot(n);
  if (pn <= 0.0) {
    next.setZero();
  } else {
    const Vec<N> pt = next - pn * n;
    const double t = pt.norm();
    if (t > c.friction * pn) {
      // Sliding: j = j_n (n + mu_k d), with j_n such that the normal velocity reaches the target.
      const Vec<N> dir = pt / t;
      const Vec<N> slide = n + c.kinetic_friction * dir;
      const double normal_mass = n.dot(p.k * n);
      const double denom = n.dot(p.k * slide);
      double jn = denom > 0.5 * normal_mass ? (target - n.dot(u) + n.dot(p.k * old)) / denom : pn;
      jn = std::max(jn, 0.0);
      next = jn * slide;
    }
  }
  apply_impulse(a, b, p, Vec<N>(next - old));
  p.impulse = next;
}

template <int N>
void load_velocities(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    s.solver_bodies[i].v = bodies[i].velocity;
    s.solver_bodies[i].w = bodies[i].angular_velocity;
  }
}

template <int N>
void store_velocities(const ContactState<N>& s, std::vector<Body<N>>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies[i].is_dynamic() || !s.awake[i]) continue;
    bodies[i].velocity = s.solver_bodies[i].v;
    bodies[i].angular_velocity = s.solver_bodies[i].w;
  }
}

template <int N>
double contact_target(const PointConstraint<N>& p, double h) {
  return p.gap > 0.0 ? -p.gap / h : 0.0;
}

template <int N>
void finish_stage(ContactState<N>& s) {
  for (const Constraint<N>& c : s.constraints)
    for (int k = c.first; k < c.first + c.count; ++k) {
      PointConstraint<N>& p = s.points[k];
      p.normal_total += p.impulse.dot(c.normal);
      p.impulse.setZero();
    }
}

// Shock propagation: the contact graph's levels in increasing order; at each level the bodies of lower
// levels (and static and kinematic bodies) are frozen, so the level's bodies come to rest on them
// without pushing them down. Constraints whose bodies are out of reach of any static body are skipped.
template <int N>
void shock_propagation(ContactState<N>& s, const ContactSettings& settings, double h) {
  const std::size_t count = s.shock_order.size();
  for (std::size_t begin = 0; begin < count;) {
    const int level = s.constraints[s.shock_order[begin]].level;
    std::size_t end = begin;
    while (end < count && s.constraints[s.shock_order[end]].level == level) ++end;
    // K of the unfrozen bodies only.
    for (std::size_t i = begin; i < end; ++i) {
      const Constraint<N>& c = s.constraints[s.shock_order[i]];
      const bool fa = s.solver_bodies[c.a].level < level, fb = s.solver_bodies[c.b].level < level;
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.points[k];
        p.k = (fa ? Mat<N>::Zero() : p.ka) + (fb ? Mat<N>::Zero() : p.kb);
        p.k_inv = p.k.inverse();
      }
    }
    for (int it = 0; it < settings.shock_iterations; ++it)
      for (std::size_t i = begin; i < end; ++i) {
        const Constraint<N>& c = s.constraints[s.shock_order[i]];
        SolverBody<N>& a = s.solver_bodies[c.a];
        SolverBody<N>& b = s.solver_bodies[c.b];
        a.frozen = a.level < level;
        b.frozen = b.level < level;
        for (int k = c.first; k < c.first + c.count; ++k) solve_point(a, b, s.points[k], c, contact_target(s.points[k], h));
        a.frozen = b.frozen = false;
      }
    begin = end;
  }
}

// Split impulses: pseudo velocities push penetrating points apart by a fraction of their depth beyond
// the slop; they move positions in this step only and never enter the kinetic energy.
template <int N>
void correct_positions(ContactState<N>& s, const ContactSettings& settings, double h) {
  for (int it = 0; it < settings.position_iterations; ++it)
    for (const Constraint<N>& c : s.constraints) {
      SolverBody<N>& a = s.solver_bodies[c.a];
      SolverBody<N>& b = s.solver_bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.points[k];
        const double excess = -p.gap - settings.linear_slop;
        if (excess <= 0.0) continue;
        const double target = settings.position_correction * excess / h;
        const double un = c.normal.dot(b.vp + dot<N>(p.rb, b.wp) - a.vp - dot<N>(p.ra, a.wp));
        const double next = std::max(p.pseudo + p.normal_mass * (target - un), 0.0);
        const Vec<N> j = (next - p.pseudo) * c.normal;
        p.pseudo = next;
        a.vp -= a.inv_mass * j;
        a.wp.c -= p.wa * j;
        b.vp += b.inv_mass * j;
        b.wp.c += p.wb * j;
      }
    }
}

}  // namespace

template <int N>
void process_collisions(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings,
                        double h) {
  // Only restitutive pairs: with e = 0 the collision pass would just stop the approach, which contact
  // processing does after the velocity update anyway.
  bool any = false;
  for (const Constraint<N>& c : s.constraints)
    if (c.restitution > 0.0)
      for (int k = c.first; k < c.first + c.count; ++k)
        any = any || (s.points[k].approach < 0.0 && s.points[k].gap + h * s.points[k].approach < 0.0);
  if (!any) return;
  load_velocities(s, bodies);
  for (int it = 0; it < settings.collision_iterations; ++it)
    for (const Constraint<N>& c : s.constraints) {
      if (c.restitution <= 0.0) continue;
      SolverBody<N>& a = s.solver_bodies[c.a];
      SolverBody<N>& b = s.solver_bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.points[k];
        if (!(p.approach < 0.0 && p.gap + h * p.approach < 0.0)) continue;
        solve_point(a, b, p, c, -c.restitution * p.approach);
      }
    }
  finish_stage(s);
  store_velocities(s, bodies);
}

template <int N>
void process_contacts(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h) {
  if (s.constraints.empty()) return;
  load_velocities(s, bodies);
  for (int it = 0; it < settings.contact_iterations; ++it)
    for (const Constraint<N>& c : s.constraints) {
      SolverBody<N>& a = s.solver_bodies[c.a];
      SolverBody<N>& b = s.solver_bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) solve_point(a, b, s.points[k], c, contact_target(s.points[k], h));
    }
  if (settings.shock_iterations > 0) shock_propagation(s, settings, h);
  finish_stage(s);
  correct_positions(s, settings, h);
  store_velocities(s, bodies);
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template void process_collisions<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double); \
  template void process_contacts<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double);
WEDGE_INSTANTIATE(2)
WEDGE_INSTANTIATE(3)
WEDGE_INSTANTIATE(4)
WEDGE_INSTANTIATE(5)
WEDGE_INSTANTIATE(6)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
