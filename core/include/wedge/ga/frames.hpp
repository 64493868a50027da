// The rotor that carries one orthonormal frame into another, by the paper's method (section 8): apply
// successive simple rotors, each turning the next axis of the source frame (as already turned) onto the
// corresponding axis of the target. Each turn is in the plane of those two axes, which is orthogonal to
// every axis matched before (both frames are orthonormal), so earlier matches stay put; after N - 1 of
// them the last axis follows from the orientation. The input layer takes the bivector part of this
// rotor as the plane and direction of the torque that turns a held body toward the hand.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/LU>  // determinant()

#include "wedge/error.hpp"
#include "wedge/ga/products.hpp"

namespace wedge {

// The simple rotor turning unit vector u onto unit vector v in their common plane (x' = R x ~R):
// R = (1 + v u) / |1 + v u|, i.e. cos(a/2) + sin(a/2) (v ^ u)/|v ^ u| for the angle a between them.
// Not for v = -u (the plane is undefined); rotor_between_frames handles that case.
template <int N>
Rotor<N> rotor_between_vectors(const Vec<N>& u, const Vec<N>& v) {
  const Rotor<N> r = Rotor<N>::from_parts(1.0 + v.dot(u), outer<N>(v, u));
  return r * (1.0 / r.norm());
}

// The rotor R with R from.col(i) ~R = to.col(i) for every i, for orthonormal frames of the same
// orientation (columns are the axes; a rotation matrix is such a frame). Throws wedge::Error if either
// frame is not orthonormal to 1e-6 or their orientations differ (no rotation maps one onto the other).
template <int N>
Rotor<N> rotor_between_frames(const Mat<N>& from, const Mat<N>& to) {
  for (const Mat<N>* f : {&from, &to}) {
    if (!all_finite(*f) || !((f->transpose() * *f - Mat<N>::Identity()).cwiseAbs().maxCoeff() <= 1e-6))
      throw Error("rotor_between_frames: a frame is not orthonormal (columns must be unit and orthogonal)");
  }
  if (from.determinant() * to.determinant() < 0.0)
    throw Error("rotor_between_frames: the frames have opposite orientations (a reflection, not a rotation)");
  // Below this, 1 + v.u loses the plane to round-off: go through a perpendicular axis instead.
  constexpr double kAntiparallel = 1e-6;
  Rotor<N> r = Rotor<N>::identity();
  for (int i = 0; i + 1 < N; ++i) {
    const Vec<N> c = rotate(r, Vec<N>(from.col(i)));
    const Vec<N> b = to.col(i);
    if (1.0 + b.dot(c) > kAntiparallel) {
      r = rotor_between_vectors<N>(c, b) * r;
    } else {
      // A half turn: the next source axis, as turned so far, is orthogonal to c and to every matched axis,
      // so c -> p -> b (two quarter turns) keeps the matched axes fixed.
      const Vec<N> p = rotate(r, Vec<N>(from.col(i + 1)));
      r = rotor_between_vectors<N>(p, b) * (rotor_between_vectors<N>(c, p) * r);
    }
  }
  return r;
}

}  // namespace wedge
