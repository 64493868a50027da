// The exponential of any bivector and the logarithm of a rotor, exact in every dimension.
//
// A general bivector is a sum of commuting simple bivectors in orthogonal planes (the invariant
// decomposition), B = sum_i t_i u_i^v_i, so exp(B) = prod_i (cos t_i + sin t_i u_i^v_i); in 4D that is a
// double rotation. 2D and 3D bivectors are always simple; 4D has a closed form through the self-dual /
// anti-self-dual split; 5D bivectors have at most two planes, whose exp has a closed form in the invariants
// |B|^2 and |B^B|^2 (exp_two_planes); 6D's sub-step turns (|B| <= 1/8) from power series in its three
// invariants (exp_three_planes), larger 6D turns peel their largest plane with one eigenvector first.
// Convention: R = exp(B) rotates u toward v by -2t in each plane, so dR/dt = -1/2 w R gives R = exp(-w t/2).
#pragma once

#include <cmath>

#include "wedge/ga/products.hpp"

namespace wedge {

// One plane of the invariant decomposition: B_i = angle * (u ^ v), with u, v orthonormal.
template <int N>
struct BivectorPlane {
  double angle = 0.0;
  Vec<N> u = Vec<N>::Zero(), v = Vec<N>::Zero();
};
template <int N>
struct BivectorDecomposition {
  std::array<BivectorPlane<N>, N / 2> planes{};
  int count = 0;
};

namespace ga::detail {

// sin(x)/x, accurate near 0.
inline double sinc(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
// cos x without the library call for small x, the same double the library gives:
// - below 2^-27 it is 1 (x^2/2 < 2^-55, under half the gap below 1);
// - below 1e-4 (sinc's series range) it is 1 - x^2 (1/2 - x^2/24): the next term, x^6/720, is under
//   1.4e-27 and the rounding of x^2 (1/2 - x^2/24) under 1e-24, against a gap of 1.1e-16 between the
//   doubles below 1, so the one rounding left, of 1 - y, lands where the library's does (checked
//   against std::cos on 2.7e8 random x in that range, and in test_exp_log.cpp).
// A resting body turns by that little in a sub-step, so this range is the common one in a resting
// pile, where the library call would be most of the rotor update.
inline double cos_near_zero(double x) {
  const double a = std::abs(x);
  if (a < 0x1p-27) return 1.0;
  if (a < 1e-4) {
    const double x2 = x * x;
    return 1.0 - x2 * (0.5 - x2 * (1.0 / 24.0));
  }
  return std::cos(x);
}

// In 4D: B -> B I for the pseudoscalar I = e0123, as a signed permutation of the 6 components.
struct Dual4 {
  std::array<int, 6> index{};
  std::array<double, 6> sign{};
};
constexpr Dual4 make_dual4() {
  constexpr auto ord = Blades<4>::order<Set::Bivector>();
  constexpr auto idx = Blades<4>::index<Set::Bivector>();
  Dual4 d{};
  for (int i = 0; i < 6; ++i) {
    d.index[i] = idx[ord[i] ^ 0xFu];
    d.sign[i] = blade_product_sign(ord[i], 0xFu);
  }
  return d;
}
inline constexpr Dual4 kDual4 = make_dual4();

inline Bivector<4> dual4(const Bivector<4>& b) {
  Bivector<4> o;
  for (int i = 0; i < 6; ++i) o[kDual4.index[i]] = kDual4.sign[i] * b[i];
  return o;
}

}  // namespace ga::detail

// Defined in src/ga/exp_log.cpp for N = 2..6: the general paths need an eigensolver, which is costly to
// compile, so it is compiled once rather than in every file that takes an exp or a log.
// Peels the planes of a skew generator matrix W (W x = x . B) one at a time, largest first: the top
// eigenvector u of W^T W, its partner v = W u / |W u|, then deflation W <- P W P with P the projector off
// span{u, v}. Re-solving after each peel keeps every plane accurate to round-off of |B| even when the
// angles differ by many orders of magnitude; an isoclinic (degenerate) eigenspace yields any valid split.
template <int N>
BivectorDecomposition<N> decompose_generator(Mat<N> w);

// exp of a general bivector by the invariant decomposition: every plane from an eigenvector (any N; a
// second, independent way to the same rotor, which the tests compare with exp).
template <int N>
Rotor<N> exp_by_decomposition(const Bivector<N>& b);

// exp of a bivector that is the sum of at most two commuting orthogonal planes, B = B1 + B2 with
// B_i = t_i u_i^v_i (every 4D and 5D bivector), from its invariants, without an eigensolver:
//   exp(B) = (c1 + sinc(t1) B1)(c2 + sinc(t2) B2) = c1 c2 + f1 B1 + f2 B2 + sinc(t1) sinc(t2) W
// with c_i = cos t_i, f1 = sinc(t1) c2, f2 = sinc(t2) c1 and W = B1 B2 = <B B>_4 / 2. The squared
// angles x_i = t_i^2 are the roots of x^2 - e1 x + e2, where e1 = |B|^2 = x1 + x2 and e2 = |W|^2 = x1 x2.
// The planes themselves are never formed: f1 B1 + f2 B2 = a B + b P with P = x2 B1 + x1 B2 = -<W B>_2,
// where a + b x2 = f1 and a + b x1 = f2, so
//   b = (f1 - f2) / (x2 - x1) = (sinc(t1 + t2) - sinc(t1 - t2)) / (2 t1 t2),   a = (f1 + f2 - b e1) / 2.
// Both are symmetric in t1, t2 and neither divides by x1 - x2, so they stay accurate where the two angles
// meet (isoclinic: the split is not unique there, and x1 - x2 is known only to sqrt(eps) |B|^2). The sums
// run on the unit bivector B / |B|, with the angles scaled back, so no invariant overflows. For large B
// the a B and b P terms are each about |B| and cancel: the rotor is exact to about eps |B|. A bivector
// with a third plane (6D) gives that plane only to first order: exp_by_invariants peels it first.
template <int N>
Rotor<N> exp_two_planes(const Bivector<N>& b);

// exp of a bivector of at most three planes (every bivector up to 7D; defined for N = 4, 5, 6) with
// |B|^2 <= 1/64, from its invariants, with neither an eigensolver nor a root:
//   exp(B) = prod_i (c_i + s_i b_i) = C + C sum_i tanc(t_i) B_i + S sum_{i<j} (t_k cot t_k) B_i B_j + S B1 B2 B3
// (c_i = cos t_i, s_i = sin t_i, B_i = t_i b_i, k the plane other than i and j, C = prod_i c_i,
// S = prod_i sin t_i / t_i). The squared angles x_i are the roots of x^3 - e1 x^2 + e2 x - e3 with
// e1 = |B|^2, e2 = |Q|^2, e3 = tau^2 for Q = <B B>_4 / 2 and T = tau I = <Q B>_6 / 3. Any power series f
// taken on the roots is a quadratic a + b x + c x^2 there (the series reduced modulo the cubic), so
//   sum_i f(x_i) B_i = a B + b B' + c B'',  B' = <Q B>_2 + e1 B,  B'' = <Q B'>_2 + p2 B,
//   sum_k g(x_k) B_i B_j = a Q - b T B - c T B',
// with p2 = sum x_i^2 = e1^2 - 2 e2, and log C, log S are sums over the roots of the series of log cos and
// log sinc: 3a + b e1 + c p2.
// Equal angles need no care: nothing divides by a difference of roots. The series converge as
// (x / 2.47)^n; the term count follows |B| (4 terms at a sub-step's typical |B| = 0.01, 8 at 1/8).
template <int N>
Rotor<N> exp_three_planes(const Bivector<N>& b);

// exp for N >= 5 and |B| <= 1 (every sub-step's turn of a body below 960 rad/s): exp_two_planes in 5D; in
// 6D exp_three_planes up to |B| = 1/8; beyond it the largest plane B1 = t u^v (u the top eigenvector of
// W^T W, v = W u / t) is peeled first, exp(B) = (cos t + sin t u^v) exp_two_planes(B - B1). Larger B go to
// exp_by_decomposition: the closed form's terms grow like |B| and cancel, so its rotor is exact only to
// eps |B| there.
template <int N>
Rotor<N> exp_by_invariants(const Bivector<N>& b);

// log of a rotor from the rotation planes of its matrix M (any N; the path used for N >= 5), such that
// exp(log R) = R including the sign of R (a full turn is R = -1). Planes turned by more than 60 degrees
// are peeled from the eigenvectors of I - (M + M^T)/2 (eigenvalue 1 - cos a); the rest from the skew part
// (M - M^T)/2 (eigenvalue sin a), where small angles keep their full precision.
template <int N>
Bivector<N> log_by_decomposition(const Rotor<N>& r);

// The invariant decomposition of any bivector into at most N/2 commuting orthogonal simple parts.
template <int N>
BivectorDecomposition<N> decompose(const Bivector<N>& b) {
  return decompose_generator<N>(generator_matrix(b));
}

template <int N>
Rotor<N> exp(const Bivector<N>& b) {
  using ga::detail::sinc;
  if constexpr (N <= 3) {  // every bivector is simple: B^2 = -|B|^2
    // (In 2D |B| = |b12|, which is what sqrt(b12^2) rounds to; where b12^2 underflows, both are below
    // 2^-27 and give the same rotor.)
    const double t = N == 2 ? std::abs(b.c[0]) : b.norm();
    return Rotor<N>::from_parts(ga::detail::cos_near_zero(t), b * sinc(t));
  } else if constexpr (N == 4) {
    // B = S + A with S I = S, A I = -A (I = e0123): S and A commute, S A = 0, and
    // exp(B) = (cos p + cos q)/2 + S sinc(p) + A sinc(q) + I (cos p - cos q)/2, p = sqrt2|S|, q = sqrt2|A|.
    const Bivector<4> bi = ga::detail::dual4(b);
    const Bivector<4> s = (b + bi) * 0.5, a = (b - bi) * 0.5;
    const double p = std::sqrt(2.0) * s.norm(), q = std::sqrt(2.0) * a.norm();
    const double cp = ga::detail::cos_near_zero(p), cq = ga::detail::cos_near_zero(q);
    Rotor<4> r = Rotor<4>::from_parts(0.5 * (cp + cq), s * sinc(p) + a * sinc(q));
    r[7] = 0.5 * (cp - cq);
    return r;
  } else {
    return exp_by_invariants(b);
  }
}

template <int N>
Bivector<N> log(const Rotor<N>& r) {
  if constexpr (N == 2) {
    return Bivector<2>::basis(0, 1) * std::atan2(r[1], r[0]);
  } else if constexpr (N == 3) {
    const Bivector<3> b = r.bivector();
    const double s = b.norm();
    if (s == 0.0) return r[0] >= 0 ? Bivector<3>{} : Bivector<3>::basis(0, 1) * M_PI;
    return b * (std::atan2(s, r[0]) / s);
  } else if constexpr (N == 4) {
    // Invert the closed form of exp: cos p = r0 + r4, cos q = r0 - r4, S_R = S sinc(p), A_R = A sinc(q).
    const Bivector<4> b = r.bivector(), bi = ga::detail::dual4(b);
    const Bivector<4> sr = (b + bi) * 0.5, ar = (b - bi) * 0.5;
    const double r4 = r[7];
    auto part = [](const Bivector<4>& x, double cosine, const Bivector<4>& half_turn) {
      const double n = x.norm();
      const double angle = std::atan2(std::sqrt(2.0) * n, cosine);  // in [0, pi]
      if (n == 0.0) return cosine >= 0 ? Bivector<4>{} : half_turn;
      return x * (angle / (std::sqrt(2.0) * n));
    };
    // Half turns (p or q = pi) have S_R = 0: use a fixed self-dual / anti-self-dual plane pair.
    Bivector<4> hs, ha;
    hs.c << M_PI / 2, 0, 0, 0, 0, -M_PI / 2;  // (pi/2)(e01 - e23): S I = S
    ha.c << M_PI / 2, 0, 0, 0, 0, M_PI / 2;   // (pi/2)(e01 + e23): A I = -A
    return part(sr, r[0] + r4, hs) + part(ar, r[0] - r4, ha);
  } else {
    return log_by_decomposition(r);
  }
}

}  // namespace wedge
