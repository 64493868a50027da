// The general (eigensolver) paths of exp and log, compiled once for N = 2..6 (see exp_log.hpp).
#include "wedge/ga/exp_log.hpp"

#include "wedge/dimensions.hpp"
#include "linalg/decompositions.hpp"

namespace wedge {

namespace {
// The plane of W through the unit vector u, which lies in one of W's planes: v = W u / |W u|, angle
// |W u|. False when the angle is round-off of `scale`.
template <int N>
bool plane_through(const Mat<N>& w, const Vec<N>& u, double scale, BivectorPlane<N>& plane) {
  const Vec<N> wu = w * u;
  const double angle = wu.norm();
  if (!(angle > 4e-16 * scale)) return false;
  plane = BivectorPlane<N>{angle, u, wu / angle};
  return true;
}
// The plane of W's largest angle, through the top eigenvector of W^T W. False also when the eigensolver
// did not converge (a generator too large to be a turn).
template <int N>
bool largest_plane(const Mat<N>& w, double scale, BivectorPlane<N>& plane) {
  linalg::SmallVector values;
  linalg::SmallMatrix vectors;
  if (!linalg::symmetric_eigen(w.transpose() * w, values, vectors)) return false;
  return plane_through<N>(w, vectors.col(N - 1), scale, plane);
}
}  // namespace

template <int N>
BivectorDecomposition<N> decompose_generator(Mat<N> w) {
  BivectorDecomposition<N> out;
  const double scale = w.norm();
  for (int p = 0; p < N / 2; ++p) {
    BivectorPlane<N> plane;
    if (p == N / 2 - 1) {
      // What is left acts on the N - 2p <= 3 dimensions not yet peeled, where every bivector is simple:
      // W = t (v u^T - u v^T), whose every column lies in the plane. The largest one, made unit, is a u
      // as good as the eigenvector (any unit u in the plane gives |W u| = t), without an eigensolver.
      int j = 0;
      w.colwise().squaredNorm().maxCoeff(&j);
      const double len = w.col(j).norm();
      if (!(len > 0.0) || !plane_through<N>(w, w.col(j) / len, scale, plane)) break;  // the rest is round-off
    } else if (!largest_plane<N>(w, scale, plane)) {
      // (an eigensolver that does not converge, for a generator too large to be a turn, ends the
      // decomposition instead of reading vectors it did not write; so does a remainder of round-off)
      break;
    }
    out.planes[out.count++] = plane;
    const Mat<N> proj = Mat<N>::Identity() - plane.u * plane.u.transpose() - plane.v * plane.v.transpose();
    w = proj * w * proj;
  }
  return out;
}

template <int N>
Rotor<N> exp_by_decomposition(const Bivector<N>& b) {
  const BivectorDecomposition<N> d = decompose(b);
  Rotor<N> r = Rotor<N>::identity();
  for (int i = 0; i < d.count; ++i) {
    const BivectorPlane<N>& p = d.planes[i];
    r = r * Rotor<N>::from_parts(std::cos(p.angle), outer<N>(p.u, p.v) * std::sin(p.angle));
  }
  return r;
}

template <int N>
Rotor<N> exp_two_planes(const Bivector<N>& b) {
  using namespace ga;
  using ga::detail::cos_near_zero;
  using ga::detail::sinc;
  const double n = b.norm();
  if (!(n > 0.0)) return Rotor<N>::identity();
  const Bivector<N> bh = b * (1.0 / n);
  // B^ B^ = -1 + 2 W^ (grade 0 and 4), W^ = B^1 B^2 for the unit bivector B^ = B / |B|.
  constexpr int k = kBiv<N>, k4 = binomial(N, 4);
  Rotor<N> wh;
  ga::detail::product<Terms<N, Set::Bivector, Set::Bivector, Set::Even, Product::Geometric>>(bh, bh, wh);
  wh.c.template head<1 + k>().setZero();
  wh.c.template segment<k4>(1 + k) *= 0.5;
  wh.c.template tail<kEven<N> - 1 - k - k4>().setZero();
  // The squared angles over |B|^2: the roots of x^2 - x + |W^|^2, the larger one from the formula and
  // the smaller as the product over it (no cancellation when one plane is much smaller).
  const double e2 = wh.c.template segment<k4>(1 + k).squaredNorm();
  const double x1 = 0.5 * (1.0 + std::sqrt(std::max(0.0, 1.0 - 4.0 * e2)));
  const double x2 = e2 / x1;
  const double tau1 = std::sqrt(x1), tau2 = std::sqrt(x2);
  const double t1 = n * tau1, t2 = n * tau2;
  const double c1 = cos_near_zero(t1), c2 = cos_near_zero(t2);
  const double s1 = n * sinc(t1), s2 = n * sinc(t2);  // sin(t_i) / tau_i
  // a^ = |B| a and b^ = |B|^3 b of the formula in exp_log.hpp, for B^ and P^ = P / |B|^3. b enters a
  // multiplied by e1, so it must be accurate to eps in both regimes: near equal angles (x2 >= 1/4) as the sinc
  // difference over 2 t1 t2, whose denominator is then near x1; where the second plane is smaller
  // (t2 < t1 / sqrt 3, down to none) as its definition (f1 - f2) / (x2 - x1), whose denominator is then
  // at least x1 / 2 while the sinc difference would cancel.
  const double bhat = x2 >= 0.25 ? n * (sinc(t1 + t2) - sinc(t1 - t2)) / (2.0 * tau1 * tau2)
                                 : (c1 * s2 - s1 * c2) / (x1 - x2);
  const double ahat = 0.5 * ((s1 * c2 + s2 * c1) - bhat * (x1 + x2));
  Bivector<N> ph;  // <W^ B^>_2 = -P^
  ga::detail::product<Terms<N, Set::Even, Set::Bivector, Set::Bivector, Product::Geometric>>(wh, bh, ph);
  Rotor<N> r = wh * (s1 * s2);  // sinc(t1) sinc(t2) W
  r.c[0] = c1 * c2;
  r.c.template segment<k>(1) = (bh * ahat - ph * bhat).c;
  return r;
}

namespace {
// Power series in x = t^2, coefficients of x^0 .. x^9 (valid for x < pi^2 / 4):
//   tan t / t = 1 + x/3 + 2x^2/15 + ..    t cot t = 1 - x/3 - x^2/45 - ..
//   log cos t = -x/2 - x^2/12 - ..       log(sin t / t) = -x/6 - x^2/180 - ..
constexpr int kSeriesTerms = 10;
constexpr double kTanc[kSeriesTerms] = {1.0,
                                        1.0 / 3.0,
                                        2.0 / 15.0,
                                        17.0 / 315.0,
                                        62.0 / 2835.0,
                                        1382.0 / 155925.0,
                                        21844.0 / 6081075.0,
                                        929569.0 / 638512875.0,
                                        6404582.0 / 10854718875.0,
                                        443861162.0 / 1856156927625.0};
constexpr double kTCot[kSeriesTerms] = {1.0,
                                        -1.0 / 3.0,
                                        -1.0 / 45.0,
                                        -2.0 / 945.0,
                                        -1.0 / 4725.0,
                                        -2.0 / 93555.0,
                                        -1382.0 / 638512875.0,
                                        -4.0 / 18243225.0,
                                        -3617.0 / 162820783125.0,
                                        -87734.0 / 38979295480125.0};
constexpr double kLogCos[kSeriesTerms] = {0.0,
                                          -1.0 / 2.0,
                                          -1.0 / 12.0,
                                          -1.0 / 45.0,
                                          -17.0 / 2520.0,
                                          -31.0 / 14175.0,
                                          -691.0 / 935550.0,
                                          -10922.0 / 42567525.0,
                                          -929569.0 / 10216206000.0,
                                          -3202291.0 / 97692469875.0};
constexpr double kLogSinc[kSeriesTerms] = {0.0,
                                           -1.0 / 6.0,
                                           -1.0 / 180.0,
                                           -1.0 / 2835.0,
                                           -1.0 / 37800.0,
                                           -1.0 / 467775.0,
                                           -691.0 / 3831077250.0,
                                           -2.0 / 127702575.0,
                                           -3617.0 / 2605132530000.0,
                                           -43867.0 / 350813659321125.0};

// A function of the squared angle on the three roots x_i of chi(x) = x^3 - s1 x^2 + s2 x - s3, as the
// quadratic a + b x + c x^2 that takes its values there: the series f_0 + f_1 x + .. + f_K x^K reduced
// modulo chi by Horner's rule (x (a + b x + c x^2) = s3 c + (a - s2 c) x + (b + s1 c) x^2 on the roots).
// No root is formed and nothing divides by a difference of roots, so equal angles need no care.
struct OnRoots {
  double a = 0.0, b = 0.0, c = 0.0;
};
OnRoots series_on_roots(const double* f, int terms, double s1, double s2, double s3) {
  OnRoots q{f[terms - 1], 0.0, 0.0};
  for (int n = terms - 2; n >= 0; --n) q = OnRoots{s3 * q.c + f[n], q.a - s2 * q.c, q.b + s1 * q.c};
  return q;
}
}  // namespace

template <int N>
Rotor<N> exp_three_planes(const Bivector<N>& b) {
  using namespace ga;
  static_assert(N >= 4);
  constexpr int k = kBiv<N>, k4 = binomial(N, 4);
  using Quad = Eigen::Matrix<double, k4, 1>;
  // The invariants: Q = <B B>_4 / 2 = sum_{i<j} t_i t_j b_i b_j and T = <Q B>_6 / 3 = t1 t2 t3 b1 b2 b3
  // (its e012345 coefficient tau), so s1 = |B|^2, s2 = |Q|^2 and s3 = tau^2 are the elementary symmetric
  // functions of the squared angles.
  Quad q = Quad::Zero();
  ga::detail::product<Terms<N, Set::Bivector, Set::Bivector, Set::Quadvector, Product::Geometric>>(b, b, q);
  q *= 0.5;
  double tau = 0.0;
  if constexpr (N == 6) {
    Eigen::Matrix<double, 1, 1> t6 = Eigen::Matrix<double, 1, 1>::Zero();
    ga::detail::product<Terms<N, Set::Quadvector, Set::Bivector, Set::Pseudoscalar, Product::Geometric>>(q, b, t6);
    tau = t6[0] / 3.0;
  }
  const double s1 = b.squared_norm(), s2 = q.squaredNorm(), s3 = tau * tau;
  // For X = sum_i y_i t_i b_i, <Q X>_2 = -sum_m t_m b_m sum_{i != m} x_i y_i (<b_i b_j b_j>_2 = -b_i), so
  // B' = sum x_i t_i b_i = <Q B>_2 + e1 B and B'' = sum x_i^2 t_i b_i = <Q B'>_2 + p2 B with p2 = sum x_i^2
  // (Newton's identity). Q' = sum x_k t_i t_j b_i b_j (k the plane left out) = -T B, and Q'' = -T B'.
  const double p2 = s1 * s1 - 2.0 * s2;
  const auto contract_q = [&](const Bivector<N>& x) {
    Bivector<N> o;
    ga::detail::product<Terms<N, Set::Quadvector, Set::Bivector, Set::Bivector, Product::Geometric>>(q, x, o);
    return o;
  };
  const Bivector<N> b1 = contract_q(b) + b * s1;
  const Bivector<N> b2 = contract_q(b1) + b * p2;
  // Every series' n-th term is below (0.42 x)^n for x <= s1 (the nearest poles are at x = pi^2 / 4): take
  // terms until that is below 1e-17.
  int terms = 1;
  for (double e = s1 * 0.42; e > 1e-17 && terms < kSeriesTerms; e *= s1 * 0.42) ++terms;
  // exp(B) = prod_i (c_i + s_i b_i) = C + C sum_i tanc(t_i) t_i b_i + S sum_k (t_k cot t_k) t_i t_j b_i b_j + S T
  // with C = prod_i cos t_i and S = prod_i sin t_i / t_i (c_i s_j s_k... regrouped around the plane that
  // differs), and sum_i f(x_i) t_i b_i = a B + b B' + c B'' for f = a + b x + c x^2 on the roots.
  const OnRoots lc = series_on_roots(kLogCos, terms, s1, s2, s3);
  const OnRoots ls = series_on_roots(kLogSinc, terms, s1, s2, s3);
  const double cos_product = std::exp(3.0 * lc.a + lc.b * s1 + lc.c * p2);
  const double sinc_product = std::exp(3.0 * ls.a + ls.b * s1 + ls.c * p2);
  const OnRoots f = series_on_roots(kTanc, terms, s1, s2, s3);
  const OnRoots g = series_on_roots(kTCot, terms, s1, s2, s3);
  Rotor<N> r;
  r.c[0] = cos_product;
  r.c.template segment<k>(1) = cos_product * (f.a * b.c + f.b * b1.c + f.c * b2.c);
  Quad grade4 = g.a * q;
  if constexpr (N == 6) {
    Quad tb = Quad::Zero(), tb1 = Quad::Zero();
    const Eigen::Matrix<double, 1, 1> t6{tau};
    ga::detail::product<Terms<N, Set::Pseudoscalar, Set::Bivector, Set::Quadvector, Product::Geometric>>(t6, b, tb);
    ga::detail::product<Terms<N, Set::Pseudoscalar, Set::Bivector, Set::Quadvector, Product::Geometric>>(t6, b1, tb1);
    grade4 -= g.b * tb + g.c * tb1;
    r.c[kEven<N> - 1] = sinc_product * tau;
  }
  r.c.template segment<k4>(1 + k) = sinc_product * grade4;
  return r;
}

template <int N>
Rotor<N> exp_by_invariants(const Bivector<N>& b) {
  using namespace ga;
  // Beyond |B| = 1 the closed form's a B and b P terms grow like |B| and cancel, so its rotor is exact
  // to eps |B| rather than eps; the eigenvectors keep larger turns (initial orientations, not the
  // sub-steps' small ones) exact to eps.
  if (!(b.squared_norm() <= 1.0)) return exp_by_decomposition(b);
  if constexpr (N == 6)
    if (b.squared_norm() <= 1.0 / 64.0) return exp_three_planes(b);
  if constexpr (N <= 5) {
    return exp_two_planes(b);
  } else {
    // Peel the largest plane B1 = t u^v, then exp(B) = (cos t + sin t u^v) exp(B - B1) (the planes commute).
    const Mat<N> w = generator_matrix(b);
    BivectorPlane<N> p;
    if (!largest_plane<N>(w, w.norm(), p)) return exp_two_planes(b);  // B is round-off
    const Bivector<N> plane = outer<N>(p.u, p.v);
    const Rotor<N> rest = exp_two_planes<N>(b - plane * p.angle);
    Rotor<N> r = rest * std::cos(p.angle);
    ga::detail::product<Terms<N, Set::Bivector, Set::Even, Set::Even, Product::Geometric>>(
        plane * std::sin(p.angle), rest, r);
    return r;
  }
}

template <int N>
Bivector<N> log_by_decomposition(const Rotor<N>& r) {
  Mat<N> m = to_matrix(r);
  Bivector<N> out;
  std::array<std::pair<double, Bivector<N>>, N> planes{};  // N/2 used; N keeps -Warray-bounds quiet
  int count = 0;
  auto add_plane = [&](const Vec<N>& u, const Vec<N>& v) {
    const Vec<N> mu = m * u;
    const double alpha = std::atan2(v.dot(mu), u.dot(mu));  // M u = cos(a) u + sin(a) v
    planes[count++] = {alpha, outer<N>(u, v)};
    out += outer<N>(u, v) * (-0.5 * alpha);
    const Mat<N> proj = Mat<N>::Identity() - u * u.transpose() - v * v.transpose();
    m = proj * m * proj + (Mat<N>::Identity() - proj);  // the peeled plane is now fixed
  };
  while (count < N / 2) {  // large turns
    const Mat<N> sym = 0.5 * (m + m.transpose());
    linalg::SmallVector values;
    linalg::SmallMatrix vectors;
    if (!linalg::symmetric_eigen(Mat<N>::Identity() - sym, values, vectors)) break;
    if (values[N - 1] < 0.5) break;
    const Vec<N> u = vectors.col(N - 1);
    Vec<N> v = m * u - u.dot(m * u) * u;
    if (v.norm() < 1e-4) {  // near a half turn: the partner is the next eigenvector of the plane
      v = vectors.col(N - 2);
      v -= u.dot(v) * u;
    }
    add_plane(u, v.normalized());
  }
  if (count < N / 2) {  // small turns
    const BivectorDecomposition<N> d = decompose_generator<N>(0.5 * (m - m.transpose()));
    for (int i = 0; i < d.count && count < N / 2; ++i) add_plane(d.planes[i].u, d.planes[i].v);
  }
  // exp(out) is +R or -R; fix the sign with a full turn (+-pi) in the most turned plane.
  if (exp_by_decomposition(out).c.dot(r.c) < 0.0) {
    if (count == 0) return Bivector<N>::basis(0, 1) * M_PI;  // R = -1
    int k = 0;
    for (int i = 1; i < count; ++i)
      if (std::abs(planes[i].first) > std::abs(planes[k].first)) k = i;
    out += planes[k].second * (planes[k].first > 0 ? M_PI : -M_PI);
  }
  return out;
}

#define WEDGE_INSTANTIATE(N)                                                        \
  template BivectorDecomposition<N> decompose_generator<N>(Mat<N>);              \
  template Rotor<N> exp_by_decomposition<N>(const Bivector<N>&);                 \
  template Rotor<N> exp_two_planes<N>(const Bivector<N>&);                       \
  template Rotor<N> exp_by_invariants<N>(const Bivector<N>&);                    \
  template Bivector<N> log_by_decomposition<N>(const Rotor<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE
template Rotor<4> exp_three_planes<4>(const Bivector<4>&);
template Rotor<5> exp_three_planes<5>(const Bivector<5>&);
template Rotor<6> exp_three_planes<6>(const Bivector<6>&);

}  // namespace wedge
