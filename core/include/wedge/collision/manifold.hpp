// What the narrow phase returns for one pair of shapes: whether they intersect, the penetration depth
// and normal, and a contact manifold of up to 2^(N-1) points with feature ids that persist from step to
// step while the same features touch (so the contact solver can warm start).
#pragma once

#include <array>
#include <cstdint>

#include "wedge/ga/types.hpp"

namespace wedge {

// Where a shape is: x_world = position + rotation * x_body (rotation = to_matrix(rotor)).
template <int N>
struct Transform {
  Vec<N> position = Vec<N>::Zero();
  Mat<N> rotation = Mat<N>::Identity();

  Vec<N> apply(const Vec<N>& x) const { return position + rotation * x; }
  Vec<N> apply_inverse(const Vec<N>& x) const { return rotation.transpose() * (x - position); }
};

template <int N>
struct ContactPoint {
  Vec<N> point = Vec<N>::Zero();  // m, world; halfway between the two surfaces
  double depth = 0.0;             // m, penetration along the normal (< 0: a gap, for speculative contacts)
  std::uint64_t id = 0;           // the pair of features that made the point; stable while they touch
};

// A face-to-face contact of two 4-cubes has the 8 corners of a 3-cube; in general the points of a face
// contact are reduced to this many while still spanning the contact region.
template <int N>
inline constexpr int kMaxManifoldPoints = 1 << (N - 1);

template <int N>
struct Manifold {
  bool intersecting = false;
  // Penetration depth along `normal` (>= 0 when intersecting). When the shapes are apart, minus their
  // distance, so depth < 0: exact (GJK) with CollisionSettings::exact_separation, else the gap along the
  // separating axis found (a lower bound of the distance). Always finite.
  double depth = 0.0;
  Vec<N> normal = Vec<N>::Zero();  // unit, from shape a towards shape b
  int count = 0;                   // contact points (0 when the shapes are apart beyond the margin)
  std::array<ContactPoint<N>, kMaxManifoldPoints<N>> points{};

  void add(const ContactPoint<N>& p) {
    if (count < kMaxManifoldPoints<N>) points[count++] = p;
  }
};

struct CollisionSettings {
  // m. Contact points with a gap up to this are reported too (negative depth), so that resting contacts
  // do not flicker on and off; 0 reports only penetrating points.
  double contact_margin = 0.0;
  // For polytope pairs that are apart, replace the separating-axis lower bound of the distance by the
  // exact distance from GJK (depth = -distance). Tools want it; a contact solver does not.
  bool exact_separation = true;
  // m. A mixed (edge) axis of the separating axis test replaces the best face axis only if it is
  // shallower by more than this, so that two nearly parallel faces keep a face-to-face manifold instead
  // of flipping to a one-point edge contact. 0 (the default) gives the exact minimum translation; the
  // contact solver uses a few millimetres, at the cost of a depth up to that much too large.
  double face_preference = 0.0;
};

}  // namespace wedge
