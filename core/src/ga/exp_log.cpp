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

template <int N>
Rotor<N> exp_by_invariants(const Bivector<N>& b) {
  using namespace ga;
  // Beyond |B| = 1 the closed form's a B and b P terms grow like |B| and cancel, so its rotor is exact
  // to eps |B| rather than eps; the eigenvectors keep larger turns (initial orientations, not the
  // sub-steps' small ones) exact to eps.
  if (!(b.squared_norm() <= 1.0)) return exp_by_decomposition(b);
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

}  // namespace wedge
