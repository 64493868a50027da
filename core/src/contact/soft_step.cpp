// The soft step (Catto, "Solver2D" 2024 and Box2D v3): each step is taken as sub-steps, and in each
//   integrate_velocities   gravity and forces (dynamics/integrate.hpp)
//   solve (use_bias)       grabs, joints, then contacts: soft normal constraints that push penetration out at
//                          a spring's rate, friction in the Coulomb cone; warm started
//   integrate_positions    x += h v, R <- exp(-h w/2) R
//   relax                  the same passes without the push, so the push leaves no velocity behind
// and once after the last sub-step restitution, from the approach speeds the step began with.
//
// Contacts are found once per step. Within it each point keeps its normal, its lever arms (the
// Jacobian) and its effective masses; what changes is its separation, computed from how far the two
// bodies have moved and turned since the step began: s = base + n . (dp_b + dq_b r_b - dp_a - dq_a r_a).
// A point still apart (s > 0) may close by s in the sub-step and no more (speculative contact); a
// penetrating one is pushed out by a soft constraint of frequency contact_hertz and damping ratio
// contact_damping_ratio, never faster than contact_push_speed. The soft constraint is implicit Euler on
// a damped spring (wedge/softness.hpp, as grabs use): mass_scale and impulse_scale blend the rigid answer
// with the accumulated impulse so the push is the same for light and heavy bodies.
//
// Why this holds stacks: a sub-step of h/4 leaves a quarter of the velocity error for the same passes,
// and the relax pass removes the push's velocity, so a stack is not thrown up by its own correction;
// the warm-started impulses of the last sub-step carry the load from one sub-step to the next.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "contact/impulses.hpp"
#include "contact/lane_fill.hpp"
#include "contact/lanes.hpp"
#include "dynamics/integrate.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/softness.hpp"

namespace wedge::contact {

namespace {

using lanes::WarmStart;
using lanes::WidePass;

// A kernel over s.soft.wide[begin, end): in 4-lane packs on AVX-512 or AVX2 (lanes_x86.cpp) where the lanes
// allow, else in 2-lane packs.
template <int N, class Kernel>
void run_lanes(ContactState<N>& s, const Kernel& kernel, int begin, int end) {
#if WEDGE_X86_LANES
  if constexpr (kWideLanes4<N>) {
    if (s.soft.lanes == Lanes::Avx512) return lanes::run_avx512(s, kernel, begin, end);
    if (s.soft.lanes == Lanes::Avx2) return lanes::run_avx2(s, kernel, begin, end);
  }
#endif
  kernel.template run<LaneTypes<N, 2>>(s, begin, end);
}

// fn(begin, end) over the wide constraints in solver order, for work that changes the bodies'
// velocities: colour by colour, each colour split over the workers in equal shares of its slots (its
// constraints share no moving body, so the shares are independent and the result bit-identical), then
// the uncoloured group (one constraint per wide constraint, in order) on this thread.
template <int N, class F>
void for_each_wide_run(ContactState<N>& s, F&& fn) {
  const int groups = int(s.soft.wide_start.size()) - 1;
  for (int g = 0; g < groups; ++g) {
    const int first = s.soft.wide_start[g], last = s.soft.wide_start[g + 1];
    if (first == last) continue;
    if (g + 1 < groups) {
      for_shares(s.workers, s.soft.wide, first, last, kLanes<N>, fn);
    } else {
      fn(first, last);
    }
  }
}
// A lane kernel over the wide constraints in solver order (for_each_wide_run).
template <int N, class Kernel>
void for_each_wide(ContactState<N>& s, const Kernel& kernel) {
  for_each_wide_run(s, [&](int begin, int end) { run_lanes(s, kernel, begin, end); });
}

// (add_pass_change: contact_system.hpp.)
template <int N>
inline void add_warm_start(SolverBody<N>& b) {
  if (b.frozen) return;
  b.v += b.warm_v;
  b.w += b.warm_w;
}
template <int N>
void set_warm_start(ContactState<N>& s) {
  for_each_body(s, int(s.solver_bodies.size()), [&](int i) {
    SolverBody<N>& b = s.solver_bodies[i];
    if (b.frozen) return;
    b.warm_v = b.v - b.v0;
    b.warm_w = b.w - b.w0;
  });
}

// Every point's accumulated impulse (the last sub-step's answer) applied to the fresh velocities. In
// the first sub-step point by point; after it body by body. The impulses act through lever arms, masses
// and inertias fixed for the step, so what they change of a body's velocities is what the last
// sub-step's warm start and passes changed, summed in warm_v and warm_w as they ran: one addition per
// body instead of a visit to every point. Each point's normal_total takes its impulse in the solve
// pass instead (count_warm_start).
template <int N>
void warm_start_substep(ContactState<N>& s) {
  if (s.soft.substep == 0) {
    snapshot_velocities(s);
    for_each_wide(s, WarmStart<N>{});
    set_warm_start(s);
    return;
  }
  for_each_body(s, int(s.solver_bodies.size()), [&](int i) { add_warm_start(s.solver_bodies[i]); });
}

// Restitution once the sub-steps are done: points that approached faster than the threshold when the
// step began and took an impulse get the normal velocity -e u_n (Box2D v3's rule). The accumulated
// impulses are the pair's (unpack_lane): warm_normal the last sub-step's, normal_impulse the step's.
// Lane l of wide constraint w; the lanes are visited in solver order (finish_soft_step).
template <int N>
void restitute_lane(ContactState<N>& s, const ContactSettings& settings, const WideConstraint<N>& w, int l) {
  using Biv = typename PointMasses<N>::Biv;
  const Constraint<N>& c = s.graph.constraints[w.constraint[l]];
  if (c.restitution <= 0.0) return;
  SolverBody<N>& a = s.solver_bodies[c.a];
  SolverBody<N>& b = s.solver_bodies[c.b];
  const BodyMass<N>& ma = s.masses[c.a];
  const BodyMass<N>& mb = s.masses[c.b];
  Pair<N>& pair = s.list.pairs[c.pair];
  for (int k = 0; k < c.count; ++k) {
    const WidePoint<N>& q = s.soft.wide_points[w.first + k];
    const double approach = s.soft.wide_approach[w.first + k][l];
    double& impulse = pair.warm_normal[k];
    double& total = pair.normal_impulse[k];
    if (approach > -settings.restitution_threshold || total <= 0.0) continue;
    Biv jn_a, jn_b;
    for (int i = 0; i < kBiv<N>; ++i) {
      jn_a[i] = q.jn_a[i][l];
      jn_b[i] = q.jn_b[i][l];
    }
    const double un = c.normal.dot(b.v - a.v) + jn_b.dot(b.w.c) - jn_a.dot(a.w.c);
    const double next = std::max(impulse - q.normal_mass[l] * (un + c.restitution * approach), 0.0);
    const double change = next - impulse;
    impulse = next;
    total += change;
    apply_normal_impulse(a, ma, b, mb, c.normal, change, Biv(inverse_inertia_times(ma, jn_a)),
                         Biv(inverse_inertia_times(mb, jn_b)));
  }
}

// The lanes' accumulated impulses of lane l of w to its pair, where the events, restitution and the
// next step's warm start read them (the soft step keeps no points; the paper's solver keeps its
// impulses in its points, keep_for_warm_start and keep_totals). The build has kept what the warm start
// matches them by (keep_warm_keys).
template <int N>
void unpack_lane(ContactState<N>& s, const WideConstraint<N>& w, int l) {
  const Constraint<N>& c = s.graph.constraints[w.constraint[l]];
  Pair<N>& pair = s.list.pairs[c.pair];
  for (int k = 0; k < c.count; ++k) {
    const WidePoint<N>& q = s.soft.wide_points[w.first + k];
    pair.warm_normal[k] = q.normal_impulse[l];
    pair.normal_impulse[k] = q.normal_total[l];
    if constexpr (N == 2) {
      pair.warm_tangent[k] = q.tangent_impulse[l] * tangent_2d(c.normal);
    } else {
      for (int j = 0; j < N; ++j) pair.warm_tangent[k][j] = q.tangent_impulse[j][l];
    }
  }
}

}  // namespace

// One solve (use_bias) or relax pass over the lanes; the relax pass, which follows the position update,
// first brings each wide constraint's separations up to date (update_separations).
template <int N>
void solve_contacts(ContactState<N>& s, const ContactSettings& settings, double h, bool use_bias,
                    bool count_warm_start) {
  const WidePass<N> pass{1.0 / h,          settings.contact_push_speed, s.soft.mass_scale * s.soft.bias_rate,
                         s.soft.mass_scale, s.soft.impulse_scale,        use_bias,
                         count_warm_start,  !use_bias};
  for_each_wide(s, pass);
}

// The lanes of one wide constraint from its constraints' points, built and prepared (prepare_points).
template <int N>
void fill_wide(ContactState<N>& s, WideConstraint<N>& w) {
  clear_slots(s, w);
  fill_wide_header(s, w);
  static const PointConstraint<N> none{};
  for (int l = 0; l < kLanes<N>; ++l) {
    if (w.constraint[l] < 0) continue;
    const Constraint<N>& c = s.graph.constraints[w.constraint[l]];
    for (int k = 0; k < w.count; ++k) {
      const PointConstraint<N>& x = k < c.count ? s.paper.points[c.first + k] : none;
      put_lane_point(s, w, k, l, c.normal, lane_point(x), masses_of(x, c.normal), x.dn_a, x.dn_b);
    }
  }
}

// Every lane's accumulated impulses to its pair, with the keys they are matched by (keep_warm_keys,
// unpack_lane), on their own: for the tests. In the step the build keeps the keys, and
// finish_soft_step unpacks each lane as it applies its restitution.
template <int N>
void unpack_wide(ContactState<N>& s) {
  s.workers.for_ranges(int(s.soft.wide.size()), kConstraintGrain / kLanes<N>, [&](int begin, int end) {
    for (int i = begin; i < end; ++i)
      for (int l = 0; l < kLanes<N>; ++l) {
        if (s.soft.wide[i].constraint[l] < 0) continue;
        const Constraint<N>& c = s.graph.constraints[s.soft.wide[i].constraint[l]];
        keep_warm_keys(s.list.pairs[c.pair], c.count);
        unpack_lane(s, s.soft.wide[i], l);
      }
  });
}

// Assigns the colour-ordered constraints to lanes: within a colour by point count, most first (so the
// lanes of a wide constraint are filled alike), kLanes<N> to a wide constraint; the uncoloured group,
// whose constraints may share bodies, one to a wide constraint in order.
template <int N>
void assign_lanes(ContactState<N>& s) {
  s.soft.wide.clear();
  s.soft.wide_inertia.clear();
  s.soft.wide_start.clear();
  const int groups = int(s.graph.colour_start.size()) - 1;
  int slots = 0;
  for (int g = 0; g < groups; ++g) {
    s.soft.wide_start.push_back(int(s.soft.wide.size()));
    const int first = s.graph.colour_start[g], last = s.graph.colour_start[g + 1];
    const int lanes = g + 1 < groups ? kLanes<N> : 1;
    std::vector<int>& order = s.soft.wide_scratch;
    order.resize(last - first);
    if (lanes == 1) {
      for (int k = first; k < last; ++k) order[k - first] = k;
    } else {
      // A counting sort, stable: most points first, in colour order among equals; no allocation.
      constexpr int kMost = kMaxManifoldPoints<N>;
      std::array<int, kMost + 2> at{};  // at[kMost - count]: where constraints of that count go
      for (int k = first; k < last; ++k) ++at[kMost - s.graph.constraints[k].count + 1];
      for (int i = 1; i < kMost + 2; ++i) at[i] += at[i - 1];
      for (int k = first; k < last; ++k) order[at[kMost - s.graph.constraints[k].count]++] = k;
    }
    for (int i = 0; i < int(order.size()); i += lanes) {
      WideConstraint<N> w;
      w.first = slots;
      for (int l = 0; l < kLanes<N>; ++l) {
        const int k = l < lanes && i + l < int(order.size()) ? order[i + l] : -1;
        w.constraint[l] = k;
        w.a[l] = k >= 0 ? s.graph.constraints[k].a : -1;
        w.b[l] = k >= 0 ? s.graph.constraints[k].b : -1;
        if (k >= 0) w.count = std::max(w.count, s.graph.constraints[k].count);
        if (k >= 0 && !s.solver_bodies[w.a[l]].frozen) w.move_a |= 1u << l;
        if (k >= 0 && !s.solver_bodies[w.b[l]].frozen) w.move_b |= 1u << l;
        if (((w.move_a >> l & 1u) && !s.masses[w.a[l]].isotropic) ||
            ((w.move_b >> l & 1u) && !s.masses[w.b[l]].isotropic))
          w.inertia = 0;
      }
      if (w.inertia >= 0) {
        w.inertia = int(s.soft.wide_inertia.size());
        s.soft.wide_inertia.emplace_back();
      }
      slots += w.count;
      s.soft.wide.push_back(w);
    }
  }
  s.soft.wide_start.push_back(int(s.soft.wide.size()));
  s.soft.wide_points.resize(slots);
  s.soft.wide_cold.resize(slots);
  s.soft.wide_approach.resize(slots);
}

template <int N>
void pack_wide(ContactState<N>& s) {
  assign_lanes(s);
  s.workers.for_ranges(int(s.soft.wide.size()), kConstraintGrain / kLanes<N>, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) fill_wide(s, s.soft.wide[i]);
  });
}

// The sub-steps' velocity integration: with neither a torque nor a gyroscopic term, a sub-step's
// integration is v = (v + dv) decay_v and w = w decay_w with the same numbers every sub-step, worked out
// here once (dynamics::integrate_velocity's arithmetic, so the same bits) and run by the solve sub-step
// in its first sweep (integrate_substep_velocity). The bodies it cannot do are listed in
// integrate_apart for integrate_velocities_apart, and the bodies alone (no constraint or grab uses them:
// load_world_inertias has marked those that are used) in `alone` for integrate_alone. The same sweep
// notes where each body the sub-steps move starts the step (start_body_motion).
template <int N>
void prepare_soft_step(ContactState<N>& s, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                       double h, const dynamics::Motion<N>* motion) {
  if (motion) s.soft.angular_models.resize(bodies.size());
  for_each_body(s, int(bodies.size()), [&](int i) {
    const Body<N>& b = bodies[i];
    SolverBody<N>& sb = s.solver_bodies[i];
    sb.alone = motion && sb.advances && !s.inertia_used[i];
    if (!sb.alone) start_body_motion(sb, b);
    if (!motion) return;
    const bool moving = moves(s, bodies, i);
    bool body_frame = false;
    if (moving) {
      dynamics::AngularModel<N>& model = s.soft.angular_models[i];
      model = dynamics::angular_model(b, *motion);
      body_frame = model.body_frame;
    }
    sb.apart = moving && body_frame && !sb.alone;  // (integrate_apart below)
    sb.integrates = moving && !body_frame && !sb.alone;
    if (sb.alone) sb.advances = false;
    if (!moving || body_frame || sb.alone) return;
    sb.dv = h * (motion->gravity + b.force * b.inv_mass);
    sb.decay_v = 1.0 / (1.0 + h * b.linear_drag);
    sb.decay_w = 1.0 / (1.0 + h * b.angular_drag);
  });
  // (From the flags: the bodies' torques and inertias are lines more each.)
  s.soft.integrate_apart.clear();
  s.soft.alone.clear();
  if (motion)
    for (int i = 0; i < int(bodies.size()); ++i) {
      if (s.solver_bodies[i].apart) s.soft.integrate_apart.push_back(i);
      if (s.solver_bodies[i].alone) s.soft.alone.push_back(i);
    }
  prepare_soft_contacts(s, settings, h);
}

template <int N>
void integrate_velocities_apart(ContactState<N>& s, const std::vector<Body<N>>& bodies,
                                const dynamics::Motion<N>& motion, double h) {
  for (const int i : s.soft.integrate_apart) {
    SolverBody<N>& sb = s.solver_bodies[i];
    if (s.soft.pass_change_pending) add_pass_change(sb);  // (before the velocities move on)
    dynamics::integrate_velocity(bodies[i], s.soft.angular_models[i], motion, h, sb.v, sb.w);
  }
}

// One body alone through the step's sub-steps: a dynamic one by dynamics::advance_alone, a kinematic one
// (whose velocities stay) sub-step by sub-step, as the sub-step loop would move it.
template <int N>
void integrate_body_alone(ContactState<N>& s, std::vector<Body<N>>& bodies, const dynamics::Motion<N>& motion,
                          double h, int substeps, bool repair_at_end, int i) {
  SolverBody<N>& sb = s.solver_bodies[i];
  Body<N>& b = bodies[i];
  if (b.is_dynamic()) {
    dynamics::advance_alone(b, s.soft.angular_models[i], motion, h, substeps, repair_at_end, sb.v, sb.w);
    return;
  }
  for (int k = 0; k < substeps; ++k) dynamics::advance_body(b, sb.v, sb.w, h, repair_at_end && k == substeps - 1);
}

template <int N>
void integrate_alone(ContactState<N>& s, std::vector<Body<N>>& bodies, const dynamics::Motion<N>& motion, double h,
                     int substeps, bool repair_at_end) {
  const std::vector<int>& alone = s.soft.alone;
  // (A body alone costs about as much as kBodyGrain / 8 bodies' sub-step.)
  s.workers.for_ranges(int(alone.size()), kBodyGrain / 8, [&](int begin, int end) {
    for (int k = begin; k < end; ++k) integrate_body_alone(s, bodies, motion, h, substeps, repair_at_end, alone[k]);
  });
}

// The sub-steps' velocities are the solver bodies', there is no split impulse, and which bodies move is
// the solver body's flag, read with its velocities (the body's own type and the awake flags would be
// two more reads per body and sub-step). The solve pass's finish, body by body, joins this sweep
// (finish_pass), and so does each body's motion since the step began, for the relax pass.
template <int N>
void integrate_substep_positions(ContactState<N>& s, std::vector<Body<N>>& bodies, double h, bool repair_now) {
  const bool track = !s.graph.constraints.empty();
  const bool finish = s.soft.solve_finish_pending;
  s.soft.solve_finish_pending = false;
  const auto advance = [&](int i) {
    SolverBody<N>& sb = s.solver_bodies[i];
    if (finish) finish_body_pass(sb);
    if (!sb.advances) return;
    Body<N>& b = bodies[i];
    dynamics::advance_body(b, sb.v, sb.w, h, repair_now);
    if (track) track_body_motion(sb, b);
  };
  // Up to 4D everything advance calls (exp, to_matrix, the rotor products, the repair) is inlined into
  // the sweep (flatten); in 5D and 6D, whose rotor products are 16 and 32 terms squared, the compiler's
  // own inlining decides.
  if constexpr (N <= 4)
    for_each_body(s, int(bodies.size()), [&](int i) __attribute__((flatten)) { advance(i); });
  else
    for_each_body(s, int(bodies.size()), advance);
}
template <int N>
void prepare_soft_contacts(ContactState<N>& s, const ContactSettings& settings, double h) {
  // One spring for every contact. (Box2D v3 doubles it against static bodies; with the 8 or 16 points
  // of a 3D or 4D face that made a light box under a heavy one chatter at 0.4-0.8 m/s.)
  const Softness soft = make_softness(std::min(settings.contact_hertz, 0.125 / h), settings.contact_damping_ratio, h);
  s.soft.bias_rate = soft.bias_rate;
  s.soft.mass_scale = soft.mass_scale;
  s.soft.impulse_scale = soft.impulse_scale;
  s.soft.substep = 0;
  s.soft.pass_change_pending = false;  // (the first sub-step's warm start sets warm_v afresh)
  s.soft.solve_finish_pending = false;
}

// A constraint's points at the start of the soft step (prepare_point).
template <int N>
void prepare_points(ContactState<N>& s, const Constraint<N>& c, bool warm_start) {
  for (int k = c.first; k < c.first + c.count; ++k) {
    PointConstraint<N>& p = s.paper.points[k];
    prepare_point(p, c.normal, p.gap, warm_start, p.warm_normal, p.warm_tangent);
  }
}

// After the solve pass, in one sweep over the solver bodies: what it changed goes to the warm start
// (add_pass_change), and v0 = v for the relax pass, which finds the velocities as this pass left them
// (the position update moves only the bodies). Each of these was a sweep of its own, eleven per sub-step
// with the tracking of the motion: together about a tenth of a 2D pyramid's step. The relax pass's
// changes join warm_v in the next sub-step's first sweep instead (pass_change_pending): the same
// additions in the same order, one sweep fewer, and none after the last sub-step, whose warm_v is not
// used. integrate_substep_positions does this sweep's work body by body as it moves them
// (solve_finish_pending, finish_body_pass), one sweep fewer again; the relax pass does it first if
// nothing has. (The velocities stay here until the step ends: integrate_substep_velocity.)
template <int N>
void finish_pass(ContactState<N>& s) {
  s.soft.solve_finish_pending = false;
  for_each_body(s, int(s.solver_bodies.size()), [&](int i) { finish_body_pass(s.solver_bodies[i]); });
}

template <int N>
void flush_pass_change(ContactState<N>& s) {
  if (!s.soft.pass_change_pending) return;
  s.soft.pass_change_pending = false;
  for_each_body(s, int(s.solver_bodies.size()), [&](int i) { add_pass_change(s.solver_bodies[i]); });
}

template <int N>
void solve_substep(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h,
                   bool use_bias) {
  bool grabs = false, joints = false;
  if (use_bias) {
    grabs = prepare_grabs(s, bodies, h);
    joints = prepare_joints(s, bodies, settings, h);
    // After the first sub-step, without grabs or joints, the velocity update joins the warm start's sweep.
    const bool fused = !s.graph.constraints.empty() && !grabs && !joints && s.soft.substep > 0;
    // (The last relax pass's changes join warm_v first, before the velocities move on: see
    // finish_pass. integrate_velocities_apart has added those of the bodies apart.)
    const bool pending = s.soft.pass_change_pending;
    s.soft.pass_change_pending = false;
    const auto add_pending = [pending](SolverBody<N>& b) {
      if (pending && !b.apart) add_pass_change(b);
    };
    if (!fused)
      for_each_body(s, int(s.solver_bodies.size()), [&](int i) {
        add_pending(s.solver_bodies[i]);
        integrate_substep_velocity(s.solver_bodies[i]);
      });
    if (s.graph.constraints.empty() && !grabs && !joints) return;
    if (!fused) {
      if (grabs) warm_start_grabs(s);
      if (joints) warm_start_joints(s, bodies);
      warm_start_substep(s);
      if (grabs) solve_grabs(s);
      if (joints) solve_joints(s, bodies, true);
      // (The grabs' and joints' impulses are left out of warm_v: they warm start on their own.)
      snapshot_velocities(s);
    } else {
      // integrate_substep_velocity, warm_start_substep and snapshot_velocities in one sweep.
      for_each_body(s, int(s.solver_bodies.size()), [&](int i) {
        SolverBody<N>& b = s.solver_bodies[i];
        add_pending(b);
        integrate_substep_velocity(b);
        add_warm_start(b);
        b.v0 = b.v;
        b.w0 = b.w;
      });
    }
  } else {
    if (s.soft.solve_finish_pending) finish_pass(s);  // (integrate_substep_positions does it as it moves the bodies)
    grabs = !s.driven.empty();
    joints = s.joints.any_active;
    if (s.graph.constraints.empty() && !grabs && !joints) return;
    if (grabs || joints) {
      if (grabs) solve_grabs(s);
      if (joints) solve_joints(s, bodies, false);
      snapshot_velocities(s);
    }  // (else v0 = v since the solve pass: finish_pass)
  }
  solve_contacts(s, settings, h, use_bias, use_bias && s.soft.substep > 0);
  if (use_bias) {
    s.soft.solve_finish_pending = true;
    ++s.soft.substep;
  } else {
    s.soft.pass_change_pending = true;
  }
}

// How far each body has moved (dp) and turned (dq) since the step began, for the relax pass's
// separations (the tests' form; integrate_substep_positions tracks each body as it moves it).
template <int N>
void track_substep_motion(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  if (s.graph.constraints.empty()) return;
  for_each_body(s, int(bodies.size()), [&](int i) {
    if (bodies[i].type == BodyType::Static || !s.islands.awake[i]) return;
    track_body_motion(s.solver_bodies[i], bodies[i]);
  });
}

template <int N>
void finish_soft_step(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings) {
  // Each lane's impulses to its pair, then its restitution, in one sweep in solver order (a lane's
  // restitution reads only its own pair, which its unpacking has written).
  if (!s.graph.constraints.empty())
    for_each_wide_run(s, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) {
        for (int l = 0; l < kLanes<N>; ++l)
          if (s.soft.wide[i].constraint[l] >= 0) {
            unpack_lane(s, s.soft.wide[i], l);
            restitute_lane(s, settings, s.soft.wide[i], l);
          }
      }
    });
  store_velocities(s, bodies);
}

bool lanes_supported(Lanes l) {
  switch (l) {
    case Lanes::Sse2:
      return true;
#if WEDGE_X86_LANES
    case Lanes::Avx2:
      return __builtin_cpu_supports("avx2");
    case Lanes::Avx512:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
#endif
    default:
      return false;
  }
}

Lanes default_lanes() {
  static const Lanes lanes = [] {
    const Lanes best = lanes_supported(Lanes::Avx512) ? Lanes::Avx512
                       : lanes_supported(Lanes::Avx2) ? Lanes::Avx2
                                                      : Lanes::Sse2;
    const char* env = std::getenv("WEDGE_SIMD");
    const std::string want = env ? env : "auto";
    constexpr std::pair<const char*, Lanes> kNames[] = {
        {"sse2", Lanes::Sse2}, {"avx2", Lanes::Avx2}, {"avx512", Lanes::Avx512}};
    for (const auto& [name, l] : kNames) {
      if (want != name) continue;
      if (lanes_supported(l)) return l;
      std::fprintf(stderr, "wedge: WEDGE_SIMD=%s: this CPU cannot run it; using auto\n", name);
      return best;
    }
    if (want != "auto")
      std::fprintf(stderr, "wedge: WEDGE_SIMD=%s is not auto, sse2, avx2 or avx512; using auto\n", want.c_str());
    return best;
  }();
  return lanes;
}

#define WEDGE_INSTANTIATE(N)                                                                                   \
  template void prepare_soft_step<N>(ContactState<N>&, const std::vector<Body<N>>&, const ContactSettings&, double,   \
                                     const dynamics::Motion<N>*);                                                 \
  template void integrate_velocities_apart<N>(ContactState<N>&, const std::vector<Body<N>>&,                      \
                                              const dynamics::Motion<N>&, double);                                \
  template void integrate_substep_positions<N>(ContactState<N>&, std::vector<Body<N>>&, double, bool);          \
  template void integrate_alone<N>(ContactState<N>&, std::vector<Body<N>>&, const dynamics::Motion<N>&, double, int, \
                                   bool);                                                                      \
  template void prepare_soft_contacts<N>(ContactState<N>&, const ContactSettings&, double);                         \
  template void solve_substep<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double, bool); \
  template void track_substep_motion<N>(ContactState<N>&, const std::vector<Body<N>>&);                       \
  template void flush_pass_change<N>(ContactState<N>&);                                                       \
  template void finish_soft_step<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&);       \
  template void assign_lanes<N>(ContactState<N>&);                                                           \
  template void fill_wide<N>(ContactState<N>&, WideConstraint<N>&);                                          \
  template void prepare_points<N>(ContactState<N>&, const Constraint<N>&, bool);                            \
  template void pack_wide<N>(ContactState<N>&);                                                              \
  template void solve_contacts<N>(ContactState<N>&, const ContactSettings&, double, bool, bool);            \
  template void unpack_wide<N>(ContactState<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
