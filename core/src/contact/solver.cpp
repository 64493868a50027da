// Collision and contact processing (paper section 6, after Guendelman, Bridson & Fedkiw 2003), as
// sequential impulses on the step's constraints, with K = delta/m + [r]_*^T I^-1 [r]_* per point.
// Friction acts in the whole (n-1)-dimensional tangent space at once, inside the Coulomb cone
// |j_t| <= mu j_n: mu = mu_s for a point at rest, mu_k for one that was slipping when the step began
// (so a sticking body breaks loose once the static cone is exceeded and slides on with mu_k). Impulses
// accumulate per stage and are clamped to push, never pull.
//
// Predicted positions: a point with gap g (m) and normal velocity u_n is where the bodies will be after
// the step to first order, g + h u_n. Collision processing (before the velocity update) acts on points
// that close within the step, giving them the separating speed -e u_n. Contact processing (after it)
// allows every point to close its gap exactly, u_n >= -max(g, 0)/h, and no more.
#include <algorithm>
#include <cmath>
#include <Eigen/LU>

#include "contact/impulses.hpp"
#include "dynamics/integrate.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

// What one visit of a point changed, N s: the normal impulse, and the largest component of the
// friction impulse. (Only the callers that need a speed divide; see speed_of.)
struct PointChange {
  double normal = 0.0, tangent = 0.0;
};

// An impulse change as a velocity change, m/s: exact along the normal (over the normal effective mass);
// for friction a measure for convergence of the same scale, not the exact change. Zero for a point
// with zero effective masses, which never receives an impulse.
template <int N>
double speed_of(const PointConstraint<N>& p, double impulse) {
  return p.normal_mass > 0.0 ? impulse / p.normal_mass : 0.0;
}

// One point, friction first and the normal last (the normal matters most): the tangential impulse that
// stops slipping if it lies in the cone |j_t| <= mu j_n (mu static or kinetic, chosen when the step
// began), else mu j_n against the slip; then the normal impulse that brings the normal velocity to the
// target, never pulling.
template <int N>
PointChange solve_point(SolverBody<N>& a, const BodyMass<N>& ma, SolverBody<N>& b, const BodyMass<N>& mb,
                        PointConstraint<N>& p, const Constraint<N>& c, double target) {
  const Vec<N>& n = c.normal;
  const Vec<N> u = relative_velocity(a, b, p);
  double un = n.dot(u);               // normal velocity
  Vec<N> friction = Vec<N>::Zero();  // this pass's change of the tangential impulse
  // (A point whose normal impulse has dropped to zero still has its friction taken back to zero here:
  // friction without a normal force would be outside every cone.)
  if (p.friction > 0.0 && (p.normal_impulse > 0.0 || !p.tangent_impulse.isZero(0.0))) {
    const Vec<N> old = p.tangent_impulse;
    const Vec<N> next = friction_update(p, n, Vec<N>(u - un * n));
    friction = next - old;
    p.tangent_impulse = next;
    // The normal velocity after the friction impulse, n . K j_t (K of the bodies that can move), so
    // the bodies are updated once for both impulses.
    un += p.kn.dot(friction);
  }
  const double next = std::max(p.normal_impulse + p.normal_mass * (target - un), 0.0);
  const double change = next - p.normal_impulse;
  apply_impulse(a, ma, b, mb, p, Vec<N>(friction + change * n));
  p.normal_impulse = next;
  return {std::abs(change), friction.cwiseAbs().maxCoeff()};
}



template <int N>
double contact_target(const PointConstraint<N>& p, double h) {
  return p.gap > 0.0 ? -p.gap / h : 0.0;
}

template <int N>
void finish_stage(ContactState<N>& s) {
  for (const Constraint<N>& c : s.graph.constraints)
    for (int k = c.first; k < c.first + c.count; ++k) {
      PointConstraint<N>& p = s.paper.points[k];
      p.normal_total += p.normal_impulse;
      p.normal_impulse = 0.0;
      p.tangent_impulse.setZero();
    }
}

// Shock propagation: the contact graph's levels in increasing order; at each level the bodies of lower
// levels (and static and kinematic bodies) are frozen, so the level's bodies come to rest on them
// without pushing them down. A level is done after shock_iterations passes, or sooner once a pass
// changes no point's normal velocity by more than shock_tolerance: most levels of a resting heap
// converge in a few passes. Constraints whose bodies are out of reach of any static body are skipped.
//
// A level also stops once its passes no longer converge: when a pass changes some velocity by as much
// as the pass before the last did (two passes, so that a zig-zag of a converging level is not taken for
// a stall). This happens when frozen supports move in ways no velocity of the bodies above can match
// (a box on two supports that move apart): Gauss-Seidel then cycles with a fixed amplitude instead of
// converging. Those cycles did harm, not just cost: their last pass leaves a random part of the
// mismatch in the velocities, and in 2D heaps that pumped columns of boxes into rocking for good.
template <int N>
void shock_propagation(ContactState<N>& s, const ContactSettings& settings, double h) {
  const std::size_t count = s.paper.shock_order.size();
  std::uint64_t tick = 0;  // counts constraint visits; PaperBody::moved and Constraint::shock_tick use it
  for (PaperBody<N>& b : s.paper.bodies) b.moved = 0;
  for (std::size_t begin = 0; begin < count;) {
    const int level = s.graph.constraints[s.paper.shock_order[begin]].level;
    std::size_t end = begin;
    while (end < count && s.graph.constraints[s.paper.shock_order[end]].level == level) ++end;
    // K of the unfrozen body only. (A frozen body that cannot move anyway, static, kinematic or
    // asleep, adds nothing to the pair's K, which then stays as build_constraints left it.)
    for (std::size_t i = begin; i < end; ++i) {
      const Constraint<N>& c = s.graph.constraints[s.paper.shock_order[i]];
      const BodyMass<N>& a = s.masses[c.a];
      const BodyMass<N>& b = s.masses[c.b];
      const bool fa = s.paper.bodies[c.a].level < level && a.inv_mass > 0.0,
                 fb = s.paper.bodies[c.b].level < level && b.inv_mass > 0.0;
      if (!fa && !fb) continue;
      const BodyMass<N>& moving = fa ? b : a;
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.paper.points[k];
        const Vec<N>& r = fa ? p.rb : p.ra;
        set_effective_masses(p, Mat<N>(moving.inv_mass * Mat<N>::Identity() + angular_mass_term(moving, r)),
                             c.normal);
      }
    }
    // After the first pass a constraint is visited again only while it can still change by more than
    // the tolerance: its own last visit did, or a neighbour has since moved one of its bodies by more.
    // In a heap this leaves the later passes to the few slow faces instead of the whole level.
    double last = 0.0, before_last = 0.0;  // m/s, the largest change of the last two passes
    for (int it = 0; it < settings.shock_iterations; ++it) {
      double largest = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        Constraint<N>& c = s.graph.constraints[s.paper.shock_order[i]];
        SolverBody<N>& a = s.solver_bodies[c.a];
        SolverBody<N>& b = s.solver_bodies[c.b];
        PaperBody<N>& pa = s.paper.bodies[c.a];
        PaperBody<N>& pb = s.paper.bodies[c.b];
        if (it > 0 && c.shock_change <= settings.shock_tolerance && pa.moved <= c.shock_tick &&
            pb.moved <= c.shock_tick)
          continue;
        a.frozen = pa.level < level;
        b.frozen = pb.level < level;
        double change = 0.0;
        for (int k = c.first; k < c.first + c.count; ++k) {
          PointConstraint<N>& q = s.paper.points[k];
          change = std::max(change,
                            speed_of(q, solve_point(a, s.masses[c.a], b, s.masses[c.b], q, c, contact_target(q, h)).normal));
        }
        c.shock_tick = ++tick;
        c.shock_change = change;
        if (change > settings.shock_tolerance) {
          if (!a.frozen) pa.moved = tick;
          if (!b.frozen) pb.moved = tick;
        }
        a.frozen = b.frozen = false;
        largest = std::max(largest, change);
      }
      if (largest <= settings.shock_tolerance || (it >= 2 && largest >= before_last)) break;
      before_last = last;
      last = largest;
    }
    begin = end;
  }
}

// Split impulses: pseudo velocities push penetrating points apart by a fraction of their depth beyond
// the slop; they move positions in this step only and never enter the kinetic energy.
template <int N>
void correct_positions(ContactState<N>& s, const ContactSettings& settings, double h) {
  for (int it = 0; it < settings.position_iterations; ++it)
    for (const Constraint<N>& c : s.graph.constraints) {
      const BodyMass<N>& a = s.masses[c.a];
      const BodyMass<N>& b = s.masses[c.b];
      PaperBody<N>& pa = s.paper.bodies[c.a];
      PaperBody<N>& pb = s.paper.bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.paper.points[k];
        const double excess = -p.gap - settings.linear_slop;
        if (excess <= 0.0) continue;
        const double target = settings.position_correction * excess / h;
        const double un = c.normal.dot(pb.vp + dot<N>(p.rb, pb.wp) - pa.vp - dot<N>(p.ra, pa.wp));
        const double next = std::max(p.pseudo + p.pseudo_mass * (target - un), 0.0);
        const Vec<N> j = (next - p.pseudo) * c.normal;
        p.pseudo = next;
        pa.vp -= a.inv_mass * j;
        pa.wp.c -= angular_change(a, p.ra, j);
        pb.vp += b.inv_mass * j;
        pb.wp.c += angular_change(b, p.rb, j);
      }
    }
}

}  // namespace

// Sequential impulses on several points at once are not guaranteed to take energy out: restitution
// with spin, and kinetic friction whose direction follows the slip, can return a little more than came
// in. So each stage ends with a check per group of bodies joined by the stage's constraints: if the
// group's kinetic energy rose, its velocity changes (equivalently, all its impulses) are scaled by the
// alpha in [0, 1) that gives back the energy it had. Momentum is unchanged, and energy never rises.
template <int N>
void limit_energy(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool restitutive_only) {
  const int n = int(bodies.size());
  s.islands.union_parent.resize(n);
  for (int i = 0; i < n; ++i) s.islands.union_parent[i] = i;
  auto root = [&s](int i) {
    while (s.islands.union_parent[i] != i) i = s.islands.union_parent[i] = s.islands.union_parent[s.islands.union_parent[i]];
    return i;
  };
  auto moves = [&](int i) { return s.masses[i].inv_mass > 0.0; };
  for (const Constraint<N>& c : s.graph.constraints)
    if ((!restitutive_only || c.restitution > 0.0) && moves(c.a) && moves(c.b)) {
      const int ra = root(c.a), rb = root(c.b);
      if (ra != rb) s.islands.union_parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  // A group with a grabbed body has an outside source of energy (the hand): it may gain energy.
  s.paper.group_driven.assign(s.driven.empty() ? 0 : n, 0);
  if (!restitutive_only)
    for (int i = 0; i < n && i < int(s.driven.size()); ++i)
      if (s.driven[i]) s.paper.group_driven[root(i)] = 1;
  // Per group root: B = sum of p0 . dv terms, C = half the energy of the changes; E(alpha) = E0 + alpha B
  // + alpha^2 C, so E(1) > E0 means B + C > 0.
  std::vector<double>& lin = s.paper.group_b;
  std::vector<double>& quad = s.paper.group_c;
  lin.assign(n, 0.0);
  quad.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (!moves(i)) continue;
    const SolverBody<N>& b = s.solver_bodies[i];
    const Vec<N> dv = b.v - b.v0;
    const Bivector<N> dw = b.w - b.w0;
    if (dv.isZero(0.0) && dw.c.isZero(0.0)) continue;  // untouched by the stage: adds nothing
    const BivMat<N> inertia = bodies[i].world_inertia();
    const int r = root(i);
    lin[r] += bodies[i].mass * b.v0.dot(dv) + b.w0.c.dot(inertia * dw.c);
    quad[r] += 0.5 * (bodies[i].mass * dv.squaredNorm() + dw.c.dot(inertia * dw.c));
  }
  for (int i = 0; i < n; ++i) {
    if (!moves(i)) continue;
    const int r = root(i);
    if (!s.paper.group_driven.empty() && s.paper.group_driven[r]) continue;
    const double b = lin[r], c = quad[r];
    if (!(b + c > 1e-12 * std::abs(b)) || !(c > 0.0)) continue;
    const double alpha = std::clamp(-b / c, 0.0, 1.0);
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.v = sb.v0 + alpha * (sb.v - sb.v0);
    sb.w = sb.w0 + (sb.w - sb.w0) * alpha;
  }
}

template <int N>
void process_collisions(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings,
                        double h) {
  // Only restitutive pairs: with e = 0 the collision pass would just stop the approach, which contact
  // processing does after the velocity update anyway.
  bool any = false;
  for (const Constraint<N>& c : s.graph.constraints)
    if (c.restitution > 0.0)
      for (int k = c.first; k < c.first + c.count; ++k)
        any = any || (s.paper.points[k].approach < 0.0 && s.paper.points[k].gap + h * s.paper.points[k].approach < 0.0);
  if (!any) return;
  load_velocities(s, bodies);
  snapshot_velocities(s);
  for (int it = 0; it < settings.collision_iterations; ++it)
    for (const Constraint<N>& c : s.graph.constraints) {
      if (c.restitution <= 0.0) continue;
      SolverBody<N>& a = s.solver_bodies[c.a];
      SolverBody<N>& b = s.solver_bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& p = s.paper.points[k];
        if (!(p.approach < 0.0 && p.gap + h * p.approach < 0.0)) continue;
        solve_point(a, s.masses[c.a], b, s.masses[c.b], p, c, -c.restitution * p.approach);
      }
    }
  limit_energy(s, bodies, true);
  finish_stage(s);
  store_velocities(s, bodies);
}

// Starts every point from the impulse its features received in the last step (applied at once).
template <int N>
void warm_start(ContactState<N>& s) {
  for (PointConstraint<N>& p : s.paper.points) {
    p.normal_impulse = p.warm_normal;
    p.tangent_impulse = p.warm_tangent;
  }
  for (const Constraint<N>& c : s.graph.constraints) apply_accumulated(s, c);
}

template <int N>
void process_contacts(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h) {
  const bool grabs = prepare_grabs(s, bodies, h);
  if (s.graph.constraints.empty() && !grabs) return;
  load_velocities(s, bodies);
  snapshot_velocities(s);
  if (settings.warm_start) {
    warm_start_grabs(s);
    warm_start(s);
  }
  // Grabs first, contacts last in every pass: the contacts have the last word, so a held body is stopped
  // by what it hits rather than pulled through it.
  for (int it = 0; it < std::max(settings.contact_iterations, grabs ? 1 : 0); ++it) {
    double largest = grabs ? solve_grabs(s) : 0.0;  // m/s
    for (const Constraint<N>& c : s.graph.constraints) {
      SolverBody<N>& a = s.solver_bodies[c.a];
      SolverBody<N>& b = s.solver_bodies[c.b];
      for (int k = c.first; k < c.first + c.count; ++k) {
        PointConstraint<N>& q = s.paper.points[k];
        const PointChange d = solve_point(a, s.masses[c.a], b, s.masses[c.b], q, c, contact_target(q, h));
        largest = std::max(largest, speed_of(q, std::max(d.normal, d.tangent)));
      }
    }
    if (largest <= settings.contact_tolerance) break;
  }
  if (settings.shock_iterations > 0) shock_propagation(s, settings, h);
  keep_for_warm_start(s);
  limit_energy(s, bodies, false);
  finish_stage(s);
  keep_totals(s);
  correct_positions(s, settings, h);
  store_velocities(s, bodies);
}

// Position half, with the new velocities plus the split-impulse pseudo velocities of position
// correction: x += h v, R <- exp(-h w/2) R (exact for constant w over the step), and, when repair_now,
// R rebuilt from unit-vector factors (dynamics::advance_body).
template <int N>
void integrate_positions(ContactState<N>& s, std::vector<Body<N>>& bodies, double h, bool repair_now) {
  const auto advance = [&](int i) {
    Body<N>& b = bodies[i];
    if (b.type == BodyType::Static || !s.islands.awake[i]) return;
    const PaperBody<N>& pb = s.paper.bodies[i];
    Vec<N>& v = b.velocity;
    Bivector<N>& w = b.angular_velocity;
    if (pb.wp.c.isZero(0.0)) {
      dynamics::advance_body(b, Vec<N>(v + pb.vp), w, h, repair_now);
      return;
    }
    // The split impulse turns the body further than its spin does. Turning the angular velocity along
    // by that extra turn Q keeps it the same in the body frame, so the correction moves the body without
    // changing its kinetic energy (1/2 w . I' w would otherwise change with I').
    b.center += h * (v + pb.vp);
    const Rotor<N> spun = exp<N>(w * (-0.5 * h)) * b.rotor;
    const Rotor<N> next = exp<N>((w + pb.wp) * (-0.5 * h)) * b.rotor;
    w = rotate(next * reverse(spun), w);
    b.rotor = repair_now ? repair(next) : next;
  };
  // (Up to 4D everything advance calls is inlined into the sweep, as in the soft step's.)
  if constexpr (N <= 4)
    for_each_body(s, int(bodies.size()), [&](int i) __attribute__((flatten)) { advance(i); });
  else
    for_each_body(s, int(bodies.size()), advance);
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template void process_collisions<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double); \
  template void process_contacts<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double); \
  template void integrate_positions<N>(ContactState<N>&, std::vector<Body<N>>&, double, bool);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
