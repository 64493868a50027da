// The soft step's lane kernels (internal): the passes, the warm start and the sub-step separations
// over a range of wide constraints (wide.hpp), templates on their lane types LT (LaneTypes).
// soft_step.cpp runs them in 2-lane packs; lanes_x86.cpp compiles them twice more in 4-lane packs, for
// AVX2 and for AVX-512 (2D, 3D; gnu::target, in that file alone), run where the CPU has them: the same
// lanes and the same IEEE operations lane by lane, so the same bits (tested). Nothing else of Wedge
// needs AVX, and Eigen's code and alignment stay those of the baseline build.
#pragma once

#include <utility>

#include "contact/contact_system.hpp"
#include "contact/impulses.hpp"
#include "wedge/ga/products.hpp"

namespace wedge::contact::lanes {

using ga::detail::apply_terms_inline;
template <int N>
using LeftContraction = ga::Terms<N, ga::Set::Vector, ga::Set::Bivector, ga::Set::Vector, ga::Product::LeftContraction>;
template <int N>
using Outer = ga::Terms<N, ga::Set::Vector, ga::Set::Vector, ga::Set::Bivector, ga::Product::Outer>;

// The wide constraint, its slots and its inertia seen through LT's lanes.
template <int N, class LT>
struct LaneView {
  using W = typename LT::W;
  using M = typename LT::M;
  using Constraint = WideConstraintT<N, W>;
  using Point = WidePointT<N, W>;
  using Cold = WidePointColdT<N, W>;
  using Inertia = WideInertiaT<N, W>;
  static const Constraint& constraint(const WideConstraint<N>& c) { return lanes_as<const Constraint>(c); }
  static Point* points(ContactState<N>& s, const WideConstraint<N>& c) {
    return &lanes_as<Point>(s.soft.wide_points[c.first]);
  }
  static Cold* cold(ContactState<N>& s, const WideConstraint<N>& c) { return &lanes_as<Cold>(s.soft.wide_cold[c.first]); }
  static const Inertia* inertia(const ContactState<N>& s, const WideConstraint<N>& c) {
    return c.inertia >= 0 ? &lanes_as<const Inertia>(s.soft.wide_inertia[c.inertia]) : nullptr;
  }
};

// The two bodies' velocities of a wide constraint, lane by lane.
template <int N, class W>
struct WideVelocities {
  static constexpr int K = kBiv<N>;
  W va[N], wa[K], vb[N], wb[K];

  template <class C>
  [[gnu::always_inline]] void gather(const std::vector<SolverBody<N>>& bodies, const C& c) {
    static const SolverBody<N> none{};
    const SolverBody<N>* a[kLanes<N>];
    const SolverBody<N>* b[kLanes<N>];
    for (int l = 0; l < kLanes<N>; ++l) {
      a[l] = c.a[l] >= 0 ? &bodies[c.a[l]] : &none;
      b[l] = c.b[l] >= 0 ? &bodies[c.b[l]] : &none;
    }
    for (int i = 0; i < N; ++i) {
      va[i] = make_wide<W>([&](int l) { return a[l]->v[i]; });
      vb[i] = make_wide<W>([&](int l) { return b[l]->v[i]; });
    }
    for (int i = 0; i < K; ++i) {
      wa[i] = make_wide<W>([&](int l) { return a[l]->w.c[i]; });
      wb[i] = make_wide<W>([&](int l) { return b[l]->w.c[i]; });
    }
  }
  // Writes back the lanes whose bodies move.
  template <class C>
  [[gnu::always_inline]] void scatter(std::vector<SolverBody<N>>& bodies, const C& c) const {
    for (int l = 0; l < kLanes<N>; ++l) {
      if (c.move_a >> l & 1u) put(bodies[c.a[l]], va, wa, l);
      if (c.move_b >> l & 1u) put(bodies[c.b[l]], vb, wb, l);
    }
  }
  [[gnu::always_inline]] static void put(SolverBody<N>& body, const W* v, const W* w, int l) {
    for (int i = 0; i < N; ++i) body.v[i] = v[i][l];
    for (int i = 0; i < K; ++i) body.w.c[i] = w[i][l];
  }
};

// The impulse j at the points' lever arms ra, rb to the lanes' velocities (apply_impulse).
template <int N, class W>
[[gnu::always_inline]] inline void apply_wide_impulse(const WideConstraintT<N, W>& c,
                                                      const WideInertiaT<N, W>* inertia, const W* ra, const W* rb,
                                                      const W* j, WideVelocities<N, W>& v) {
  constexpr int K = kBiv<N>;
  W ta[K] = {}, tb[K] = {};
  apply_terms_inline<Outer<N>::table>(ra, j, ta, std::make_index_sequence<Outer<N>::table.size()>{});
  apply_terms_inline<Outer<N>::table>(rb, j, tb, std::make_index_sequence<Outer<N>::table.size()>{});
  for (int i = 0; i < N; ++i) {
    v.va[i] -= c.inv_mass_a * j[i];
    v.vb[i] += c.inv_mass_b * j[i];
  }
  if (!inertia) {
    for (int i = 0; i < K; ++i) {
      v.wa[i] -= c.iso_a * ta[i];
      v.wb[i] += c.iso_b * tb[i];
    }
    return;
  }
  for (int i = 0; i < K; ++i) {
    W da = inertia->a[i] * ta[0], db = inertia->b[i] * tb[0];
    for (int k = 1; k < K; ++k) {
      da += inertia->a[k * K + i] * ta[k];
      db += inertia->b[k * K + i] * tb[k];
    }
    v.wa[i] -= da;
    v.wb[i] += db;
  }
}

// 2D (wide.hpp): the impulse j, whose moments about the centres are ta = ra ^ j and tb = rb ^ j (as
// jn and jt: the lever arms are not kept), to the lanes' velocities.
template <class W>
[[gnu::always_inline]] inline void apply_wide_impulse_2d(const WideConstraintT<2, W>& c,
                                                         const WideInertiaT<2, W>* inertia, const W* j, const W& ta,
                                                         const W& tb, WideVelocities<2, W>& v) {
  for (int i = 0; i < 2; ++i) {
    v.va[i] -= c.inv_mass_a * j[i];
    v.vb[i] += c.inv_mass_b * j[i];
  }
  v.wa[0] -= (inertia ? inertia->a[0] : c.iso_a) * ta;
  v.wb[0] += (inertia ? inertia->b[0] : c.iso_b) * tb;
}

// fn(c, points, cold, inertia, v) for each wide constraint of s.soft.wide[begin, end), seen through LT's lanes, its
// bodies' velocities v gathered into lanes before and written back after (the passes and the warm start).
template <int N, class LT, class F>
[[gnu::always_inline]] inline void visit_lanes(ContactState<N>& s, int begin, int end, F&& fn) {
  using View = LaneView<N, LT>;
  for (int i = begin; i < end; ++i) {
    const WideConstraint<N>& stored = s.soft.wide[i];
    const auto& c = View::constraint(stored);
    WideVelocities<N, typename LT::W> v;
    v.gather(s.solver_bodies, c);
    fn(c, View::points(s, stored), View::cold(s, stored), View::inertia(s, stored), v);
    v.scatter(s.solver_bodies, c);
  }
}

// Friction outside the cone, lane by lane (friction_update's slow branch): kinetic friction against the
// slip the point had when the step began, or the cone's nearest impulse in the tangent mass's metric.
// (Out of line and by reference: the rare path, and plain scalar code whatever the lanes.)
template <int N, class W, class M>
[[gnu::noinline]] void clamp_to_cones(const WideConstraintT<N, W>& c, const WidePointT<N, W>& p,
                                      const WidePointColdT<N, W>& cold, const W* slip, W* next, const W& limit,
                                      const M& outside) {
  for (int l = 0; l < kLanes<N>; ++l) {
    if (!outside[l]) continue;
    Vec<N> n, sl, nx, dir;
    Mat<N> tm;
    for (int i = 0; i < N; ++i) {
      n[i] = c.normal[i][l];
      sl[i] = slip[i][l];
      nx[i] = next[i][l];
      dir[i] = cold.slip_direction[i][l];
    }
    for (int i = 0; i < N * N; ++i) tm.data()[i] = p.tangent_mass[i][l];
    const bool forward = cold.sliding[l] > 0.0 && sl.dot(dir) > 0.0;
    const Vec<N> j = forward ? Vec<N>(dir * -limit[l]) : project_to_cone(tm, n, nx, limit[l]);
    for (int i = 0; i < N; ++i) next[i].set(l, j[i]);
  }
}

// m^T v, one Eigen dot product per coefficient (read lane by lane into the wide separations).
template <int N>
Vec<N> transpose_times(const Mat<N>& m, const Vec<N>& v) {
  Vec<N> o;
  for (int i = 0; i < N; ++i) o[i] = m.col(i).dot(v);
  return o;
}

// Lane l's normal, from the wide constraint's header. The separations take it and the lane's bodies
// (c.a, c.b) from there, copies of its Constraint's, which they then need not read: 88 bytes more per
// 2D constraint and relax pass to stream.
template <int N, class C>
[[gnu::always_inline]] inline Vec<N> lane_normal(const C& c, int l) {
  Vec<N> n;
  for (int i = 0; i < N; ++i) n[i] = c.normal[i][l];
  return n;
}

// update_separations in 3D-6D, from the lever arms.
template <int N, class W, class C, class P, class Cold>
[[gnu::always_inline]] inline void update_separations_nd(const ContactState<N>& s, const C& c, P* points,
                                                         const Cold* cold) {
  double moved[kLanes<N>];
  Vec<N> na[kLanes<N>], nb[kLanes<N>];
  for (int l = 0; l < kLanes<N>; ++l) {
    if (c.constraint[l] < 0) {
      moved[l] = 0.0;
      na[l].setZero();
      nb[l].setZero();
      continue;
    }
    const Vec<N> normal = lane_normal<N>(c, l);
    const SolverBody<N>& a = s.solver_bodies[c.a[l]];
    const SolverBody<N>& b = s.solver_bodies[c.b[l]];
    moved[l] = normal.dot(b.dp - a.dp);
    na[l] = transpose_times(a.dq, normal);
    nb[l] = transpose_times(b.dq, normal);
  }
  const W m = make_wide<W>([&](int l) { return moved[l]; });
  W wa[N], wb[N];
  for (int j = 0; j < N; ++j) {
    wa[j] = make_wide<W>([&](int l) { return na[l][j]; });
    wb[j] = make_wide<W>([&](int l) { return nb[l][j]; });
  }
  for (int k = 0; k < c.count; ++k) {
    auto& p = points[k];
    p.separation = cold[k].base_separation + m + wide_dot<N>(wb, p.rb) - wide_dot<N>(wa, p.ra);
  }
}

// The sub-step's separations of wide constraint c's slots from the bodies' motion since the step began
// (track_substep_motion): s = base + n . (dp_b - dp_a) + (dq_b^T n) . rb - (dq_a^T n) . ra, the turned
// normal once per pair. The relax pass forms them as it reaches each wide constraint, before its
// normals: the next solve pass sees the same positions, and a sweep of their own streamed the slots
// once more per sub-step.
template <int N, class W, class C, class P, class Cold>
[[gnu::always_inline]] inline void update_separations(const ContactState<N>& s, const C& c, P* points,
                                                      const Cold* cold) {
  if constexpr (N == 2) {
    // n . (dq r) = jt n^T dq n - jn n^T dq t, with r = jt n - jn t (wide.hpp). (Per lane: gathering
    // dp and dq into lanes took more instructions and time.)
    double moved[kLanes<2>], nn_a[kLanes<2>], nt_a[kLanes<2>], nn_b[kLanes<2>], nt_b[kLanes<2>];
    for (int l = 0; l < kLanes<2>; ++l) {
      moved[l] = nn_a[l] = nt_a[l] = nn_b[l] = nt_b[l] = 0.0;
      if (c.constraint[l] < 0) continue;
      const Vec<2> normal = lane_normal<2>(c, l);
      const SolverBody<2>& a = s.solver_bodies[c.a[l]];
      const SolverBody<2>& b = s.solver_bodies[c.b[l]];
      const Vec<2> t = tangent_2d(normal);
      moved[l] = normal.dot(b.dp - a.dp);
      nn_a[l] = normal.dot(a.dq * normal);
      nt_a[l] = normal.dot(a.dq * t);
      nn_b[l] = normal.dot(b.dq * normal);
      nt_b[l] = normal.dot(b.dq * t);
    }
    const W m = make_wide<W>([&](int l) { return moved[l]; });
    const W an = make_wide<W>([&](int l) { return nn_a[l]; }), at = make_wide<W>([&](int l) { return nt_a[l]; });
    const W bn = make_wide<W>([&](int l) { return nn_b[l]; }), bt = make_wide<W>([&](int l) { return nt_b[l]; });
    for (int k = 0; k < c.count; ++k) {
      auto& p = points[k];
      p.separation = cold[k].base_separation + m + (p.jt_b * bn - p.jn_b[0] * bt) - (p.jt_a * an - p.jn_a[0] * at);
    }
  } else {
    update_separations_nd<N, W>(s, c, points, cold);
  }
}

// One pass over wide constraints: the normal impulses first (soft when use_bias and penetrating),
// then friction in the cone of the updated normal impulse, kLanes<N> constraints at once.
template <int N>
struct WidePass {
  static constexpr int K = kBiv<N>;
  double inv_h, push_speed, bias_scale, mass_scale, impulse_scale;
  bool use_bias;
  bool count_warm_start;  // normal_total takes the warm-start impulse first (solve_contacts)
  bool separations;       // the relax pass: each wide constraint's separations first (update_separations)

  template <class W, class M>
  [[gnu::always_inline]] void normal(const WideConstraintT<N, W>& c, const WideInertiaT<N, W>* inertia, int slot,
                                     WidePointT<N, W>& p, WideVelocities<N, W>& v) const {
    if (count_warm_start) p.normal_total += p.normal_impulse;
    const W sep = p.separation;
    const M apart = sep > 0.0;  // speculative: may close the gap within the sub-step, no more
    W bias = sep * inv_h, ms = splat<W>(1.0), is = splat<W>(0.0);
    if (use_bias) {
      bias = select(apart, bias, wide_max(bias_scale * sep, splat<W>(-push_speed)));
      ms = select(apart, ms, splat<W>(mass_scale));
      is = select(apart, is, splat<W>(impulse_scale));
    } else {
      bias = select(apart, bias, splat<W>(0.0));
    }
    W du[N];
    for (int i = 0; i < N; ++i) du[i] = v.vb[i] - v.va[i];
    const W un = wide_dot<N>(c.normal, du) + wide_dot<K>(p.jn_b, v.wb) - wide_dot<K>(p.jn_a, v.wa);
    const W next = wide_max(p.normal_impulse - p.normal_mass * (ms * un + bias) - is * p.normal_impulse, splat<W>(0.0));
    const W change = next - p.normal_impulse;
    p.normal_impulse = next;
    p.normal_total += change;
    const W ca = c.inv_mass_a * change, cb = c.inv_mass_b * change;
    for (int i = 0; i < N; ++i) {
      v.va[i] -= ca * c.normal[i];
      v.vb[i] += cb * c.normal[i];
    }
    // The angular velocity change per unit normal impulse, I^-1 jn: for isotropic bodies formed here
    // rather than kept per point (a sixth of a 3D point's bytes, which the passes stream through), else
    // kept beside the inertia matrices.
    if (!inertia) {
      for (int i = 0; i < K; ++i) {
        v.wa[i] -= change * (c.iso_a * p.jn_a[i]);
        v.wb[i] += change * (c.iso_b * p.jn_b[i]);
      }
      return;
    }
    for (int i = 0; i < K; ++i) {
      v.wa[i] -= change * inertia->dn_a[slot][i];
      v.wb[i] += change * inertia->dn_b[slot][i];
    }
  }

  template <class W, class M>
  [[gnu::always_inline]] void friction(const WideConstraintT<N, W>& c, const WideInertiaT<N, W>* inertia,
                                       WidePointT<N, W>& p, const WidePointColdT<N, W>& cold,
                                       WideVelocities<N, W>& v) const {
    if constexpr (N == 2) {
      friction_2d<W, M>(c, inertia, p, cold, v);
      return;
    } else {
      friction_nd<W, M>(c, inertia, p, cold, v);
    }
  }

  // 2D: one impulse along t (wide.hpp). Outside the cone, kinetic friction against the slip the point
  // had when the step began, else the cone's end nearest the update (in one dimension the nearest point
  // in any metric: project_to_cone's answer).
  template <class W, class M>
  [[gnu::always_inline]] void friction_2d(const WideConstraintT<N, W>& c, const WideInertiaT<N, W>* inertia,
                                          WidePointT<N, W>& p, const WidePointColdT<N, W>& cold,
                                          WideVelocities<N, W>& v) const {
    M held = p.normal_impulse > 0.0;
    held |= p.tangent_impulse != 0.0;
    const M active = (p.friction > 0.0) & held;
    if (!any(active)) return;
    const W t0 = c.normal[1] * -1.0, t1 = c.normal[0];
    const W ut = (t0 * (v.vb[0] - v.va[0]) + t1 * (v.vb[1] - v.va[1])) + (p.jt_b * v.wb[0] - p.jt_a * v.wa[0]);
    W next = p.tangent_impulse - p.tangent_mass * ut;
    const W limit = p.friction * p.normal_impulse;
    const M outside = active & (next * next > limit * limit);
    if (any(outside)) {
      // (A point with no normal impulse holds no friction, sliding or not: limit 0 gives 0 either way.)
      const W d = t0 * cold.slip_direction[0] + t1 * cold.slip_direction[1];  // the slip's direction along t
      const M forward = (cold.sliding > 0.0) & (ut * d > 0.0);
      const W end = select(next < 0.0, limit * -1.0, limit);
      next = select(outside, select(forward, d * (limit * -1.0), end), next);
    }
    next = select(active, next, p.tangent_impulse);
    const W change = next - p.tangent_impulse;
    p.tangent_impulse = next;
    const W j[2] = {change * t0, change * t1};
    apply_wide_impulse_2d(c, inertia, j, change * p.jt_a, change * p.jt_b, v);
  }

  template <class W, class M>
  [[gnu::always_inline]] void friction_nd(const WideConstraintT<N, W>& c, const WideInertiaT<N, W>* inertia,
                                          WidePointT<N, W>& p, const WidePointColdT<N, W>& cold,
                                          WideVelocities<N, W>& v) const {
    M held = p.normal_impulse > 0.0;
    for (int i = 0; i < N; ++i) held |= p.tangent_impulse[i] != 0.0;
    const M active = (p.friction > 0.0) & held;
    if (!any(active)) return;
    W ca[N] = {}, cb[N] = {};  // r . w
    constexpr auto terms = std::make_index_sequence<LeftContraction<N>::table.size()>{};
    apply_terms_inline<LeftContraction<N>::table>(p.ra, v.wa, ca, terms);
    apply_terms_inline<LeftContraction<N>::table>(p.rb, v.wb, cb, terms);
    W u[N], slip[N], next[N];
    for (int i = 0; i < N; ++i) u[i] = ((v.vb[i] + cb[i]) - v.va[i]) - ca[i];
    const W un = wide_dot<N>(c.normal, u);
    for (int i = 0; i < N; ++i) slip[i] = u[i] - un * c.normal[i];
    for (int i = 0; i < N; ++i) {
      W t = p.tangent_mass[i] * slip[0];
      for (int k = 1; k < N; ++k) t += p.tangent_mass[k * N + i] * slip[k];
      next[i] = p.tangent_impulse[i] - t;
    }
    const W limit = p.friction * p.normal_impulse;
    M outside = active & (wide_dot<N>(next, next) > limit * limit);
    if (any(outside)) {
      // A point with no normal impulse holds no friction, sliding or not (as project_to_cone, and
      // as the sliding answer -limit * direction): no call for that. A resting pyramid's side contacts,
      // touching with no load while their boxes settle, had been half of all calls. The rest go lane by
      // lane.
      const M unloaded = outside & (limit <= 0.0);
      if (any(unloaded)) {
        for (int i = 0; i < N; ++i) next[i] = select(unloaded, splat<W>(0.0), next[i]);
        outside = outside & ~unloaded;
      }
      if (any(outside)) clamp_to_cones(c, p, cold, slip, next, limit, outside);
    }
    W change[N];
    for (int i = 0; i < N; ++i) {
      next[i] = select(active, next[i], p.tangent_impulse[i]);
      change[i] = next[i] - p.tangent_impulse[i];
      p.tangent_impulse[i] = next[i];
    }
    apply_wide_impulse(c, inertia, p.ra, p.rb, change, v);
  }

  // The pass over s.soft.wide[begin, end).
  template <class LT>
  [[gnu::always_inline]] void run(ContactState<N>& s, int begin, int end) const {
    using W = typename LT::W;
    using M = typename LT::M;
    // (Forced inline, as every lane operation: a call would pass the lanes through memory.)
    const auto pass = [this, &s](const auto& c, auto* points, const auto* cold, const auto* inertia, auto& v)
                          __attribute__((always_inline)) {
      if (separations) update_separations<N, W>(s, c, points, cold);
      for (int k = 0; k < c.count; ++k) normal<W, M>(c, inertia, k, points[k], v);
      for (int k = 0; k < c.count; ++k) friction<W, M>(c, inertia, points[k], cold[k], v);
    };
    visit_lanes<N, LT>(s, begin, end, pass);
  }
};

// Applies every point's accumulated impulse (the last sub-step's answer) to the fresh velocities.
template <int N>
struct WarmStart {
  template <class LT>
  [[gnu::always_inline]] void run(ContactState<N>& s, int begin, int end) const {
    using W = typename LT::W;
    const auto warm = [](const auto& c, auto* points, const auto*, const auto* inertia, auto& v)
                          __attribute__((always_inline)) {
      for (int k = 0; k < c.count; ++k) {
        auto& p = points[k];
        p.normal_total += p.normal_impulse;
        if constexpr (N == 2) {
          const W t0 = c.normal[1] * -1.0, t1 = c.normal[0];
          const W j[2] = {p.normal_impulse * c.normal[0] + p.tangent_impulse * t0,
                          p.normal_impulse * c.normal[1] + p.tangent_impulse * t1};
          apply_wide_impulse_2d(c, inertia, j, p.normal_impulse * p.jn_a[0] + p.tangent_impulse * p.jt_a,
                                p.normal_impulse * p.jn_b[0] + p.tangent_impulse * p.jt_b, v);
        } else {
          W j[N];
          for (int d = 0; d < N; ++d) j[d] = p.normal_impulse * c.normal[d] + p.tangent_impulse[d];
          apply_wide_impulse(c, inertia, p.ra, p.rb, j, v);
        }
      }
    };
    visit_lanes<N, LT>(s, begin, end, warm);
  }
};

// kernel.run over s.soft.wide[begin, end) in 4-lane packs, compiled for AVX2 (lanes_x86.cpp; 2D and 3D).
// (The target attribute is part of the function's identity for GCC: declared as defined.)
#if WEDGE_X86_LANES
template <int N, class Kernel>
[[gnu::target("avx2")]] void run_avx2(ContactState<N>& s, const Kernel& kernel, int begin, int end);
// The same compiled for AVX-512, whose 32 vector registers hold what AVX2's 16 spill to the stack.
template <int N, class Kernel>
[[gnu::target(WEDGE_AVX512_TARGET)]] void run_avx512(ContactState<N>& s, const Kernel& kernel, int begin, int end);
#endif

}  // namespace wedge::contact::lanes
