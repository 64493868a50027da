// The general (eigensolver) paths of exp and log, compiled once for N = 2..6 (see exp_log.hpp).
#include "wedge/ga/exp_log.hpp"

#include "wedge/dimensions.hpp"
#include "linalg/decompositions.hpp"

namespace wedge {

template <int N>
BivectorDecomposition<N> decompose_generator(Mat<N> w) {
  BivectorDecomposition<N> out;
  const double scale = w.norm();
  for (int p = 0; p < N / 2; ++p) {
    Vec<N> u;
    if (p == N / 2 - 1) {
      // What is left acts on the N - 2p <= 3 dimensions not yet peeled, where every bivector is simple:
      // W = t (v u^T - u v^T), whose every column lies in the plane. The largest one, made unit, is a u
      // as good as the eigenvector (any unit u in the plane gives |W u| = t), without an eigensolver.
      int j = 0;
      w.colwise().squaredNorm().maxCoeff(&j);
      const double len = w.col(j).norm();
      if (!(len > 0.0)) break;
      u = w.col(j) / len;
    } else {
      linalg::SmallVector values;
      linalg::SmallMatrix vectors;
      // (an eigensolver that does not converge, for a generator too large to be a turn, ends the
      // decomposition instead of reading vectors it did not write)
      if (!linalg::symmetric_eigen(w.transpose() * w, values, vectors)) break;
      u = vectors.col(N - 1);
    }
    const Vec<N> wu = w * u;
    const double angle = wu.norm();
    if (!(angle > 4e-16 * scale)) break;  // the rest is round-off
    const Vec<N> v = wu / angle;
    out.planes[out.count++] = BivectorPlane<N>{angle, u, v};
    const Mat<N> proj = Mat<N>::Identity() - u * u.transpose() - v * v.transpose();
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
  template Bivector<N> log_by_decomposition<N>(const Rotor<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
