// The soft step's constraints in lanes (Box2D v3's wide constraints, in double precision, any n).
//
// Each colour's constraints are packed kLanes at a time into a WideConstraint: lane l holds the l-th
// constraint's normal and bodies, and slot k of its points (a WidePoint) holds every lane's k-th point,
// field by field, so one vector instruction updates kLanes contact points. The constraints of a colour
// share no moving body, so the lanes are independent; a lane without a constraint, or past its
// constraint's last point, has no mass and takes no impulse. Velocities are gathered into lanes once
// per constraint and pass, and written back once.
//
// A Wide is P packs of L doubles, GCC's generic vectors (also Clang's): stored as 16-byte packs (one SSE2
// register on baseline x86-64, NEON elsewhere), and read as 32-byte packs by the AVX2 and AVX-512
// kernels (lanes.hpp, lanes_x86.cpp). Every lane is plain IEEE double arithmetic, so the results do not depend
// on the instruction set. The lanes a constraint goes to are fixed by the colour order alone, so the
// results do not depend on the worker count either.
#pragma once

#include <cstdint>
#include <cstring>

#include "wedge/collision/manifold.hpp"
#include "wedge/ga/types.hpp"

namespace wedge::contact {

// Lanes come in packs of two doubles (one SSE2 register); a Wide is P of them. Two packs give the
// processor twice the independent chains per instruction (GCC's own 32-byte vectors, lowered to SSE2,
// went through memory lane by lane and stalled on the store buffer; compiled for AVX2 they are native,
// LaneTypes<N, 4>); from 4D on, two packs of a body's velocities no longer fit the registers and one
// is faster (kLanes).
// Every operation is forced inline: one left as a call passes its packs through memory.
#define WEDGE_WIDE_INLINE [[gnu::always_inline]] inline

// Whether the soft step may run its lanes in AVX2's or AVX-512's 4-lane packs (x86 with GCC or Clang;
// chosen at run time, contact_system.hpp, Lanes).
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define WEDGE_X86_LANES 1
// AVX-512's kernels use its 256- and 128-bit forms too (VL) and its double-precision logic (DQ).
#define WEDGE_AVX512_TARGET "avx2,avx512f,avx512vl,avx512dq"
#else
#define WEDGE_X86_LANES 0
#endif

// A pack: L doubles in one register (16 bytes on SSE2 or NEON, 32 on AVX); its comparisons give
// lanes of -1 or 0.
template <int L>
struct PackOf;
template <>
struct PackOf<2> {
  using Value = double __attribute__((vector_size(16)));
  using Mask = std::int64_t __attribute__((vector_size(16)));
};
template <>
struct PackOf<4> {  // aligned as the 16-byte packs, so that AVX lanes can read SSE2 lanes' storage
  // (typedef, not using: Clang ignores the alignment attribute on an alias declaration)
  typedef double Value __attribute__((vector_size(32), aligned(16)));
  typedef std::int64_t Mask __attribute__((vector_size(32), aligned(16)));
};

// P packs of L lanes.
template <int P, int L = 2>
struct WideT {
  static constexpr int kPackLanes = L;
  using Pack = typename PackOf<L>::Value;
  Pack p[P];
  WEDGE_WIDE_INLINE double operator[](int l) const { return p[l / L][l % L]; }
  // (Lane l is the l-th double of the packs, whatever their width: one store.)
  void set(int l, double x) { std::memcpy(reinterpret_cast<char*>(p) + sizeof(double) * l, &x, sizeof(double)); }
};
template <int P, int L = 2>
struct WideMaskT {
  using Pack = typename PackOf<L>::Mask;
  Pack p[P];
  WEDGE_WIDE_INLINE bool operator[](int l) const { return p[l / L][l % L] != 0; }
};

// Lane-wise arithmetic, with doubles taken as every lane's value.
#define WEDGE_WIDE_OP(OP)                                                                         \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideT<P, L> operator OP(WideT<P, L> a, const WideT<P, L>& b) {                \
    for (int i = 0; i < P; ++i) a.p[i] = a.p[i] OP b.p[i];                                        \
    return a;                                                                                     \
  }                                                                                               \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideT<P, L> operator OP(WideT<P, L> a, double b) {                            \
    for (int i = 0; i < P; ++i) a.p[i] = a.p[i] OP b;                                             \
    return a;                                                                                     \
  }                                                                                               \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideT<P, L> operator OP(double a, WideT<P, L> b) {                            \
    for (int i = 0; i < P; ++i) b.p[i] = a OP b.p[i];                                             \
    return b;                                                                                     \
  }                                                                                               \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideT<P, L>& operator OP##=(WideT<P, L>& a, const WideT<P, L>& b) {           \
    return a = a OP b;                                                                            \
  }
WEDGE_WIDE_OP(+)
WEDGE_WIDE_OP(-)
WEDGE_WIDE_OP(*)
#undef WEDGE_WIDE_OP
#define WEDGE_WIDE_COMPARE(OP)                                                                    \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideMaskT<P, L> operator OP(const WideT<P, L>& a, const WideT<P, L>& b) {     \
    WideMaskT<P, L> m;                                                                            \
    for (int i = 0; i < P; ++i) m.p[i] = a.p[i] OP b.p[i];                                        \
    return m;                                                                                     \
  }                                                                                               \
  template <int P, int L>                                                                         \
  WEDGE_WIDE_INLINE WideMaskT<P, L> operator OP(const WideT<P, L>& a, double b) {                 \
    WideMaskT<P, L> m;                                                                            \
    for (int i = 0; i < P; ++i) m.p[i] = a.p[i] OP b;                                             \
    return m;                                                                                     \
  }
WEDGE_WIDE_COMPARE(<)
WEDGE_WIDE_COMPARE(>)
WEDGE_WIDE_COMPARE(!=)
WEDGE_WIDE_COMPARE(<=)
#undef WEDGE_WIDE_COMPARE
template <int P, int L>
WEDGE_WIDE_INLINE WideMaskT<P, L> operator&(WideMaskT<P, L> a, const WideMaskT<P, L>& b) {
  for (int i = 0; i < P; ++i) a.p[i] &= b.p[i];
  return a;
}
template <int P, int L>
WEDGE_WIDE_INLINE WideMaskT<P, L> operator~(WideMaskT<P, L> a) {
  for (int i = 0; i < P; ++i) a.p[i] = ~a.p[i];
  return a;
}
template <int P, int L>
WEDGE_WIDE_INLINE WideMaskT<P, L>& operator|=(WideMaskT<P, L>& a, const WideMaskT<P, L>& b) {
  for (int i = 0; i < P; ++i) a.p[i] |= b.p[i];
  return a;
}
// m ? a : b, lane by lane.
template <int P, int L>
WEDGE_WIDE_INLINE WideT<P, L> select(const WideMaskT<P, L>& m, const WideT<P, L>& a, const WideT<P, L>& b) {
  WideT<P, L> r;
  for (int i = 0; i < P; ++i) r.p[i] = m.p[i] ? a.p[i] : b.p[i];
  return r;
}
template <int P, int L>
WEDGE_WIDE_INLINE bool any(const WideMaskT<P, L>& m) {
  auto x = m.p[0];
  for (int i = 1; i < P; ++i) x |= m.p[i];
  std::int64_t r = 0;
  for (int l = 0; l < L; ++l) r |= x[l];
  return r != 0;
}

// A wide value from f(0), .., f(lanes - 1), built in registers: a pack read back from separate scalar
// stores to memory would stall on the store buffer.
template <class W, class F>
WEDGE_WIDE_INLINE W make_wide(F&& f) {
  W w;
  constexpr int L = W::kPackLanes;
  for (int i = 0; i < int(sizeof(W::p) / sizeof(w.p[0])); ++i) {
    if constexpr (L == 2) {
      w.p[i] = typename W::Pack{f(2 * i), f(2 * i + 1)};
    } else {
      w.p[i] = typename W::Pack{f(4 * i), f(4 * i + 1), f(4 * i + 2), f(4 * i + 3)};
    }
  }
  return w;
}

// Every lane x (splat), the larger of x and y per lane (std::max's answer), and sum_i x_i y_i per lane.
template <class W>
WEDGE_WIDE_INLINE W splat(double x) {
  return make_wide<W>([x](int) { return x; });
}
template <class W>
WEDGE_WIDE_INLINE W wide_max(const W& x, const W& y) {  // std::max per lane
  return select(x < y, y, x);
}
template <int K, class W>
WEDGE_WIDE_INLINE W wide_dot(const W* x, const W* y) {
  W sum = x[0] * y[0];
  for (int i = 1; i < K; ++i) sum += x[i] * y[i];
  return sum;
}

template <int N>
inline constexpr int kLanes = N == 2 ? 8 : N <= 3 ? 4 : 2;

// The lane types of one pack width L: 2 (SSE2, NEON) or 4 (AVX). The storage below is always in
// 2-lane packs; the soft step's passes may read it as 4-lane packs where the CPU has AVX2 and L divides
// kLanes (2D, 3D): the same bytes, the same lanes, the same IEEE operations lane by lane, so the same bits.
template <int N, int L>
struct LaneTypes {
  static constexpr int kPackLanes = L;
  using W = WideT<kLanes<N> / L, L>;
  using M = WideMaskT<kLanes<N> / L, L>;
};
template <int N>
using Wide = typename LaneTypes<N, 2>::W;
template <int N>
using WideMask = typename LaneTypes<N, 2>::M;
template <int N>
inline constexpr bool kWideLanes4 = kLanes<N> % 4 == 0;

// Slot k of a wide constraint: every lane's k-th point (zero where a lane has none), the fields that
// the solve and relax passes read. The passes stream these through the cache 16 times a step (a resting pyramid's
// do not fit it): what they do not read lives apart, in WidePointCold.
template <int N, class W = Wide<N>>
struct WidePointT {
  static constexpr int K = kBiv<N>;
  W separation, normal_mass, normal_impulse, normal_total;  // as PointConstraint
  W jn_a[K], jn_b[K];  // the normal's rows of the Jacobian (I^-1 jn: formed in the pass, or WideInertia's)
  W friction;
  W tangent_impulse[N], ra[N], rb[N];
  W tangent_mass[N * N];  // column-major, as Eigen's
};

// In 2D the tangent space is one line, t = (-n_1, n_0), and friction one number per point: its impulse
// along t, t's row of the Jacobian, jt = r ^ t = n . r (t . (r . w) = jt w), and its effective mass
// 1/(t^T K t), which is (P K P + n n^T)^-1 on t exactly. The lever arms need not be kept either: r =
// jt n - jn t, so the relax pass's n . (dq r) = jt n^T dq n - jn n^T dq t. 11 doubles a point instead
// of 17 (the 100-row pyramid's slots do not fit the cache), and one update and a clamp instead of a
// 2 x 2 product and the cone's projection.
inline Vec<2> tangent_2d(const Vec<2>& n) { return Vec<2>(-n[1], n[0]); }
template <class W>
struct WidePointT<2, W> {
  static constexpr int K = 1;
  W separation, normal_mass, normal_impulse, normal_total;  // as PointConstraint
  W jn_a[K], jn_b[K];
  W friction;
  W tangent_impulse;  // N s, along t
  W jt_a, jt_b;
  W tangent_mass;     // 1 / (t^T K t)
};

// The rest of slot k: read by the sub-step's separations and by friction outside the cone only.
template <int N, class W = Wide<N>>
struct WidePointColdT {
  W base_separation;
  W sliding;  // 1 or 0
  W slip_direction[N];
};

// kLanes<N> constraints of one colour.
template <int N, class W = Wide<N>>
struct WideConstraintT {
  W normal[N];
  W inv_mass_a, inv_mass_b;  // 1/kg, 0 for a body that does not move
  W iso_a, iso_b;            // isotropic inverse inertia (0 for a body that does not move)
  int a[kLanes<N>], b[kLanes<N>];     // solver bodies; -1 in an empty lane
  int constraint[kLanes<N>];       // index into constraints; -1 in an empty lane
  int first = 0, count = 0;     // its slots: wide_points and wide_cold[first .. first + count)
  int inertia = -1;             // wide_inertia index when a moving body is not isotropic, else -1
  unsigned move_a = 0, move_b = 0;  // bit l: lane l's body moves (its velocities are written back)
};

// The inverse inertia matrices of a wide constraint whose bodies are not all isotropic, and each slot's
// I^-1 jn (for isotropic bodies the normal pass forms it from jn with one product per component; here
// it would take a matrix product per point and pass).
template <int N, class W = Wide<N>>
struct WideInertiaT {
  W a[kBiv<N> * kBiv<N>], b[kBiv<N> * kBiv<N>];  // column-major (0 for a body that does not move)
  W dn_a[kMaxManifoldPoints<N>][kBiv<N>], dn_b[kMaxManifoldPoints<N>][kBiv<N>];
};

template <int N>
using WidePoint = WidePointT<N>;
template <int N>
using WidePointCold = WidePointColdT<N>;
template <int N>
using WideConstraint = WideConstraintT<N>;
template <int N>
using WideInertia = WideInertiaT<N>;

// x (stored in 2-lane packs) seen through the lane types T of another pack width: same size, same
// alignment, the same members at the same places (the lanes' bytes do not depend on the pack width).
template <class T, class S>
WEDGE_WIDE_INLINE T& lanes_as(S& x) {
  static_assert(sizeof(T) == sizeof(S) && alignof(T) == alignof(S));
  return *reinterpret_cast<T*>(&x);
}

}  // namespace wedge::contact
