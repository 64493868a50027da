// The friction cone's slow path: the impulse in the cone nearest to the unconstrained one in the metric
// of the point's tangential effective mass (impulses.hpp says why and how).
#include <cmath>
#include <Eigen/Cholesky>

#include "contact/impulses.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

template <int N>
Vec<N> project_to_cone(const Mat<N>& tangent_mass, const Vec<N>& n, const Vec<N>& unconstrained, double limit) {
  const double norm0 = unconstrained.norm();
  if (limit <= 0.0) return Vec<N>::Zero();
  Vec<N> j = unconstrained * (limit / norm0);  // (the radial answer: exact when M is isotropic)
  if (tangent_mass.isZero(0.0)) return j;
  double lambda = 0.0;
  for (int it = 0; it < 50; ++it) {
    // x = (1 + lambda T)^-1 j* and dx = d x / d lambda = -(1 + lambda T)^-1 T x; at lambda = 0 (the first
    // round) the matrix is the identity, so no factorisation is needed.
    Vec<N> x = unconstrained, dx;
    if (lambda > 0.0) {
      const Eigen::LLT<Mat<N>> llt(Mat<N>::Identity() + lambda * tangent_mass);
      x = llt.solve(unconstrained);
      dx = -llt.solve(tangent_mass * x);
    } else {
      dx = -(tangent_mass * x);
    }
    const double len = x.norm();
    if (!(len > 0.0)) break;
    j = x;
    if (std::abs(len - limit) <= 1e-13 * limit) break;
    const double dpsi = -x.dot(dx) / (len * len * len);  // d (1/|x|) / d lambda > 0
    if (!(dpsi > 0.0)) break;
    lambda += (1.0 / limit - 1.0 / len) / dpsi;
    if (!(lambda >= 0.0)) lambda = 0.0;
  }
  j -= n * n.dot(j);                 // (tangent to round-off; make it exactly so)
  return j * (limit / j.norm());     // on the cone's surface
}

#define WEDGE_INSTANTIATE(N) \
  template Vec<N> project_to_cone<N>(const Mat<N>&, const Vec<N>&, const Vec<N>&, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
