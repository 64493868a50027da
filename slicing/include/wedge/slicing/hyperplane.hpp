// A hyperplane {x : normal . x = offset} of R^N with an orthonormal frame of its own (N-1)D coordinates.
// A point y of the slice's space sits in the world at offset * normal + frame * y, so the frame columns
// are the slice's axes. The frame is right-handed with the normal: det[frame, normal] = +1, which keeps
// outward faces outward in the slice (slicer.hpp).
#pragma once

#include <Eigen/Core>

#include "wedge/ga/types.hpp"

namespace wedge::slicing {

template <int N>
struct Hyperplane {
  using Frame = Eigen::Matrix<double, N, N - 1>;
  Vec<N> normal = Vec<N>::Unit(N - 1);
  double offset = 0.0;
  Frame frame = Frame::Identity();  // e0 .. e(N-2)

  // The default slice: x_{N-1} = w (w in 4D), with the frame e0 .. e(N-2).
  static Hyperplane axis(double w) {
    Hyperplane h;
    h.offset = w;
    return h;
  }
  // normal . x = offset for any non-zero finite normal (it is normalised, and offset divided by its
  // length). The frame is the Householder reflection that takes e(N-1) to the normal, with its first
  // column negated to make it right-handed; for normal = e(N-1) it is e0 .. e(N-2). Throws wedge::Error.
  static Hyperplane through(const Vec<N>& normal, double offset);

  // The world point of slice coordinates y, and the slice coordinates of a world point (projected).
  Vec<N> to_world(const Eigen::Matrix<double, N - 1, 1>& y) const { return offset * normal + frame * y; }
  Eigen::Matrix<double, N - 1, 1> to_slice(const Vec<N>& x) const { return frame.transpose() * x; }
};

}  // namespace wedge::slicing
