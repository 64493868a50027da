// Box against box: the separating axis test of paper section 7.2, Eberly's oriented-box test extended to
// N dimensions. Working in a's frame (b's axes are the columns of C = Ra^T Rb), the candidate axes are
//   - a's N face normals e_i and b's N face normals C_j;
//   - for k = 1..N-2, the normal of the span of k axes S of a and N-1-k axes T of b. It is orthogonal to
//     e_s (s in S), so it lives in the other N-k coordinates, where it is the generalised cross product
//     of the N-1-k columns C_t restricted to them: a cross product in N-k dimensions, not N.
// In 4D that is 8 face normals plus 24 + 24 = 48 mixed axes. A box is centrally symmetric, so the overlap
// along a unit axis L is r_a + r_b - |L . d| with r = sum |L . axis| h (d: centre to centre).
#include <array>
#include <cmath>

#include "collision/narrow.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {
namespace {

// The subsets of {0..N-1} with K elements, as bit masks, in increasing order (computed at compile time).
template <int N, int K>
constexpr auto subsets() {
  constexpr int count = [] {
    int c = 0;
    for (unsigned s = 0; s < (1u << N); ++s) c += bit_count(s) == K;
    return c;
  }();
  std::array<unsigned, count> out{};
  for (unsigned s = 0, i = 0; s < (1u << N); ++s)
    if (bit_count(s) == K) out[i++] = s;
  return out;
}

template <int N>
struct BoxSat {
  const Vec<N>& ha;
  const Vec<N>& hb;
  Mat<N> c, abs_c;  // b's axes in a's frame, and their absolute values
  Vec<N> d;         // b's centre minus a's, in a's frame
  SatAxis<N> best;  // the normal is kept in a's frame until the end
  double tie = 0.0, margin = 0.0, prefer = 0.0;
  SatAxis<N> sep;  // the axis that separates the boxes beyond the margin, if one does

  // `slack`: how much shallower than the best so far the axis must be (face preference, mixed axes).
  // A gap within the round-off band (tie) is touching, not apart.
  bool consider(double pen, const Vec<N>& axis_a, double along, int facet_a, int facet_b, double slack = 0.0) {
    const Vec<N> axis = along < 0.0 ? Vec<N>(-axis_a) : axis_a;
    if (pen < best.pen - tie - slack) best = {pen, axis, facet_a, facet_b};
    if (pen >= -margin - tie) return true;
    sep = {pen, axis, facet_a, facet_b};
    return false;
  }

  // The mixed axes with |S| = K axes of a. M = N - K coordinates remain.
  template <int K>
  bool mixed() {
    constexpr int M = N - K;
    static constexpr auto kA = subsets<N, K>();
    static constexpr auto kB = subsets<N, M - 1>();
    for (const unsigned s : kA) {
      int rest[M];
      for (int i = 0, r = 0; i < N; ++i)
        if (!(s >> i & 1)) rest[r++] = i;
      for (const unsigned t : kB) {
        Eigen::Matrix<double, M, M - 1> span;
        for (int j = 0, col = 0; j < N; ++j)
          if (t >> j & 1) {
            for (int r = 0; r < M; ++r) span(r, col) = c(rest[r], j);
            ++col;
          }
        const Vec<M> l = orthogonal_complement<M>(span, 1e-6);
        if (l.isZero()) continue;  // b's axes lie (nearly) in a's: the face axes cover this direction
        Vec<N> axis = Vec<N>::Zero();
        double ra = 0.0;
        for (int r = 0; r < M; ++r) {
          axis[rest[r]] = l[r];
          ra += std::abs(l[r]) * ha[rest[r]];
        }
        const double rb = (c.transpose() * axis).cwiseAbs().dot(hb);
        const double along = axis.dot(d);
        if (!consider(ra + rb - std::abs(along), axis, along, -1, -1, prefer)) return false;
      }
    }
    return true;
  }

  template <int K>
  bool all_mixed() {
    if constexpr (K > N - 2) {
      return true;
    } else {
      return mixed<K>() && all_mixed<K + 1>();
    }
  }
};

}  // namespace

template <int N>
Manifold<N> box_box(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                    const CollisionSettings& settings) {
  const Vec<N>& ha = a.template as<shapes::Box<N>>().half_extents;
  const Vec<N>& hb = b.template as<shapes::Box<N>>().half_extents;
  const Mat<N> c = ta.rotation.transpose() * tb.rotation;
  BoxSat<N> sat{ha,
                hb,
                c,
                c.cwiseAbs(),
                ta.rotation.transpose() * (tb.position - ta.position),
                SatAxis<N>{},
                round_off_band(std::max(ha.norm(), hb.norm())),
                settings.contact_margin,
                settings.face_preference,
                SatAxis<N>{}};
  Manifold<N> m;
  bool apart = false;
  for (int i = 0; i < N && !apart; ++i)  // a's faces: facet 2i + 1 is +e_i, 2i is -e_i
    apart = !sat.consider(ha[i] + sat.abs_c.row(i).dot(hb) - std::abs(sat.d[i]), Vec<N>::Unit(i), sat.d[i],
                          2 * i + (sat.d[i] >= 0.0), -1);
  for (int j = 0; j < N && !apart; ++j) {  // b's faces; b's outward facet faces a, so its sign is opposite
    const double along = sat.c.col(j).dot(sat.d);
    apart = !sat.consider(sat.abs_c.col(j).dot(ha) + hb[j] - std::abs(along), sat.c.col(j), along, -1,
                          2 * j + (along < 0.0));
  }
  if (!apart) apart = !sat.template all_mixed<1>();
  if (apart) {  // minus the gap along the separating axis: a lower bound the dispatcher may refine
    m.intersecting = false;
    m.depth = sat.sep.pen;
    m.normal = ta.rotation * sat.sep.normal;
    return m;
  }
  SatAxis<N> best = sat.best;
  best.normal = ta.rotation * best.normal;
  m.intersecting = best.pen >= 0.0;
  m.depth = best.pen;
  m.normal = best.normal;
  sat_manifold(*a.features(), ta, *b.features(), tb, best, settings.contact_margin + sat.tie, m);
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                                \
  template Manifold<N> box_box<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, const Transform<N>&, \
                                  const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
