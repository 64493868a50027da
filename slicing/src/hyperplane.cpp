#include "wedge/slicing/hyperplane.hpp"

#include <cmath>

#include "wedge/error.hpp"

namespace wedge::slicing {

template <int N>
Hyperplane<N> Hyperplane<N>::through(const Vec<N>& normal, double offset) {
  const double len = normal.norm();
  if (!all_finite(normal) || !std::isfinite(offset) || !(len > 1e-12) || !std::isfinite(len))
    throw Error("slice hyperplane: the normal must be finite and non-zero and the offset finite");
  Hyperplane h;
  h.normal = normal / len;
  h.offset = offset / len;
  const Vec<N> v = Vec<N>::Unit(N - 1) - h.normal;
  Mat<N> m = Mat<N>::Identity();
  if (v.squaredNorm() > 1e-300) m -= 2.0 * v * v.transpose() / v.squaredNorm();  // reflection: det -1
  h.frame = m.template leftCols<N - 1>();
  h.normal = m.col(N - 1);  // = the normal up to round-off; exactly orthogonal to the frame
  if (v.squaredNorm() > 1e-300) h.frame.col(0) = -h.frame.col(0);  // det[frame, normal] = +1
  return h;
}

template struct Hyperplane<2>;
template struct Hyperplane<3>;
template struct Hyperplane<4>;
template struct Hyperplane<5>;
template struct Hyperplane<6>;

}  // namespace wedge::slicing
