// Internal: the per-family narrow-phase functions behind the dispatch table, and the pieces they share
// (support functions, support sets, face clipping, manifold reduction).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "linalg/fixed_size.hpp"
#include "wedge/collision/manifold.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/shape.hpp"

namespace wedge::collision {

template <int N>
using PairFn = Manifold<N> (*)(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b,
                               const Transform<N>& tb, const CollisionSettings& settings);

template <int N> Manifold<N> ball_ball(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);
template <int N> Manifold<N> ball_convex(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);
template <int N> Manifold<N> halfspace_convex(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);
template <int N> Manifold<N> box_box(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);
template <int N> Manifold<N> polytope_polytope(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);
template <int N> Manifold<N> convex_convex(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, const CollisionSettings&);

// ---- support (support.cpp) ----
// The point of the shape (body frame) farthest along d; bounded shapes only.
template <int N>
Vec<N> local_support(const Shape<N>& shape, const Vec<N>& d);
// The same in the world.
template <int N>
Vec<N> world_support(const Shape<N>& shape, const Transform<N>& t, const Vec<N>& d) {
  return t.apply(local_support(shape, Vec<N>(t.rotation.transpose() * d)));
}
// Points of the shape's face that is extreme along d (body frame): the vertices within `tolerance`
// (m) of the maximum for polytopes and boxes; for round products one point per ball factor not
// orthogonal to d, or a ring of points on its boundary when it is (a flat end), and both ends of an
// interval orthogonal to d. Each point comes with an id that names its feature.
template <int N>
struct SupportPoint {
  Vec<N> point;
  std::uint32_t id;
};
template <int N>
void local_support_set(const Shape<N>& shape, const Vec<N>& d, double tolerance, std::vector<SupportPoint<N>>& out);
// A box or round product as its list of ball and interval factors (a box: N intervals); no copy.
template <int N>
const std::vector<ProductFactor>& product_factors(const Shape<N>& shape);
// Whether the body-frame point lies in the shape grown by `tolerance` (m).
template <int N>
bool local_contains(const Shape<N>& shape, const Vec<N>& x, double tolerance);
// A length scale of a bounded shape (its circumradius about the body origin, bounded above).
template <int N>
double shape_scale(const Shape<N>& shape);

// ---- manifolds (clip.cpp) ----
// Reduces to kMaxManifoldPoints points that still span the contact region: the deepest point, then
// repeatedly the point farthest from those kept (deterministic: ties go to the lower index).
template <int N>
void reduce_into(const std::vector<ContactPoint<N>>& points, Manifold<N>& m);
// The manifold seen from the other side (normal reversed).
template <int N>
Manifold<N> flipped(Manifold<N> m) {
  m.normal = -m.normal;
  return m;
}
// Bits set in v. Portable SWAR: without -mpopcnt (not in the x86-64 baseline Debian builds for) the
// builtin becomes a libgcc call, which dominated face clipping.
constexpr int bit_count(std::uint64_t v) {
  v = v - ((v >> 1) & 0x5555555555555555ULL);
  v = (v & 0x3333333333333333ULL) + ((v >> 2) & 0x3333333333333333ULL);
  v = (v + (v >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
  return int((v * 0x0101010101010101ULL) >> 56);
}
// The round-off band of a pair whose length scale is `scale` (m): features that touch exactly compute as
// overlapping or apart by ~1e-16 m at random, so a gap below this counts as touching, not apart, and
// contact points within it of the margin are kept (a face resting on a face keeps its whole manifold).
inline double round_off_band(double scale) { return 1e-9 * scale; }
// Mixes feature ids into one 64-bit id.
inline std::uint64_t mix_id(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h;
}

// ---- face clipping (clip.cpp) ----
// A point of a face being clipped, with the set of constraints it is tight against (two bits per
// 64-bit word: the incident face's own boundary in `own`, the clipping planes in `clip`).
template <int N>
struct ClipPoint {
  Vec<N> x;
  std::uint64_t own = 0, clip = 0;
};
// Sutherland-Hodgman in N dimensions: clips the convex (N-1)-dimensional face given by its vertices
// (with their tight sets) against the half-spaces normal . x <= offset. Two points are joined by an edge
// when they share at least N-2 tight constraints, which holds for every edge; pairs that are not edges
// only add points inside the clipped face, never lose one of its vertices.
template <int N>
void clip_face(std::vector<ClipPoint<N>>& face, const std::vector<Vec<N>>& normals, const std::vector<double>& offsets,
               double eps);

// Contact points of a face-to-face contact: the incident face (world points with tight sets) clipped to the
// reference face's side planes, kept where they lie within `margin` of the reference plane
// (ref_normal . x <= ref_offset + margin); the normal of the manifold is set by the caller.
template <int N>
void face_contact(std::vector<ClipPoint<N>>& incident, const std::vector<Vec<N>>& side_normals,
                  const std::vector<double>& side_offsets, const Vec<N>& ref_normal, double ref_offset,
                  double margin, double scale, std::uint64_t feature_id, std::vector<ContactPoint<N>>& out);

}  // namespace wedge::collision

namespace wedge::collision {

// A unit vector orthogonal to the N-1 given vectors (the generalised cross product: components are the
// signed (N-1)x(N-1) minors), or zero when they are linearly dependent to within `tolerance` (the
// volume they span, relative to the product of their lengths).
template <int N>
Vec<N> orthogonal_complement(const Eigen::Matrix<double, N, N - 1>& m, double tolerance = 1e-9) {
  Vec<N> n;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N - 1, N - 1> minor;
    for (int r = 0, k = 0; r < N; ++r)
      if (r != i) minor.row(k++) = m.row(r);
    n[i] = (i % 2 ? -1.0 : 1.0) * linalg::determinant<N - 1>(minor);
  }
  double lengths = 1.0;
  for (int c = 0; c < N - 1; ++c) lengths *= m.col(c).norm();
  const double len = n.norm();
  if (!(len > tolerance * lengths)) return Vec<N>::Zero();
  return n / len;
}

// The face-lattice bits of a facet's vertices: bit j is set when the vertex also lies on the facet's
// j-th ridge neighbour (so vertices joined by an edge share N-2 bits).
template <int N>
void facet_clip_points(const ConvexFeatures<N>& f, int facet, const Transform<N>& t, std::vector<ClipPoint<N>>& out) {
  out.clear();
  const auto& fc = f.facets[facet];
  for (int v : fc.vertices) {
    ClipPoint<N> p{t.apply(f.vertices[v]), 0, 0};
    for (std::size_t j = 0; j < fc.neighbours.size(); ++j) {
      const auto& nv = f.facets[fc.neighbours[j]].vertices;
      if (std::binary_search(nv.begin(), nv.end(), v)) p.own |= std::uint64_t(1) << (j % 64);
    }
    out.push_back(p);
  }
}

// The side planes of a facet (its ridge neighbours' planes), in the world.
template <int N>
void facet_side_planes(const ConvexFeatures<N>& f, int facet, const Transform<N>& t, std::vector<Vec<N>>& normals,
                       std::vector<double>& offsets) {
  normals.clear();
  offsets.clear();
  for (int g : f.facets[facet].neighbours) {
    const Vec<N> n = t.rotation * f.facets[g].normal;
    normals.push_back(n);
    offsets.push_back(f.facets[g].offset + n.dot(t.position));
  }
}

}  // namespace wedge::collision

namespace wedge::collision {

// The result of a separating axis test: the axis of least overlap.
template <int N>
struct SatAxis {
  double pen = std::numeric_limits<double>::infinity();  // overlap along `normal` (a -> b); < 0: a gap
  Vec<N> normal = Vec<N>::Zero();                        // unit, a -> b
  int facet_a = -1, facet_b = -1;                        // a facet of a or of b; both -1 for a mixed axis
};

// The contact points for the SAT's axis (polytope_polytope.cpp): a facet axis clips the most
// anti-parallel facet of the other shape to the reference facet; a mixed axis gives the one point where
// the two supporting features come closest.
template <int N>
void sat_manifold(const ConvexFeatures<N>& fa, const Transform<N>& ta, const ConvexFeatures<N>& fb,
                  const Transform<N>& tb, const SatAxis<N>& best, double margin, Manifold<N>& m);

}  // namespace wedge::collision
