// Tracking space -> world (the paper's section 8: "any position the user can see corresponds to a
// position in 4D"). Tracking x, y, z (metres, y up) go along the world's first three axes, which span
// the visible slice; the remaining coordinates are the slice's offsets, held in `origin`. So in 4D a
// hand at tracking point p is at origin + scale (p_x, p_y, p_z, 0), with origin_w the slice's w.
// In 2D the tracking z is dropped and only the turn about z remains of an orientation.
#pragma once

#include <Eigen/Geometry>

#include "wedge/ga/products.hpp"

namespace wedge::input {

template <int N>
struct TrackingSpace {
  Vec<N> origin = Vec<N>::Zero();  // m, world: where the tracking origin is (its hidden coordinates
                                   // are the slice offsets)
  double scale = 1.0;              // world metres per tracking metre, > 0

  Vec<N> point(const Eigen::Vector3d& p) const { return origin + scale * vector(p); }
  Vec<N> vector(const Eigen::Vector3d& v) const {
    Vec<N> x = Vec<N>::Zero();
    for (int i = 0; i < std::min(N, 3); ++i) x[i] = v[i];
    return x;
  }
  // The controller's frame as a rotation of the world (identity on the hidden axes), as a matrix whose
  // columns are the controller's axes.
  static Mat<N> frame(const Eigen::Quaterniond& q) {
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    Mat<N> m = Mat<N>::Identity();
    if constexpr (N == 2) {
      const double a = std::atan2(r(1, 0), r(0, 0));  // the turn about z
      m << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    } else {
      m.template topLeftCorner<3, 3>() = r;
    }
    return m;
  }
};

}  // namespace wedge::input
