// Contact recycling (after Box2D v3, Catto 2025): a pair whose bodies have barely moved relative to each
// other since its manifold was computed keeps that manifold. Its points stay attached to the two bodies
// (each lever arm turns with its body), its normal stays fixed in the world, and only each point's
// separation is brought up to date: gap = gap0 + n . ((c_b - c_a) + arm_b - arm_a), which is exact for
// the attached points. This is what holds tall stacks still. A freshly computed manifold lets each
// support's normal tilt with the support, and the column leans further on the tilted normals until the
// soft contacts' small give grows into a collapse; Box2D v3 itself drops a 30-box tower without it.
// It also skips the narrow phase for most resting pairs.
//
// Only pairs of flat-faced shapes (boxes, polytopes, meshes as hulls, half-spaces) with contact points
// are recycled: a round shape's contact point slides over its surface as it rolls. A pair is recycled
// while neither body has turned by more than recycle_angle since, and the relative motion moves no
// point of the larger body by more than about recycle_distance: |dp| + radius * angle(dQ) <
// recycle_distance, dQ the relative turn, radius the larger body's farthest point from its centre.
#include <algorithm>
#include <cmath>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

// The angle of the turn q p^T between two rotation matrices, as |q p^T - 1|_F / sqrt(2) (exact for a
// small turn in one plane, larger for turns in several). For rotations |Q - 1|_F^2 = 2 (N - tr Q), and
// tr(q p^T) is the sum of the elementwise products: N^2 products instead of a matrix product and a
// norm. (Round-off in N - tr leaves angles below about 3e-8 rad unresolved: far under recycle_angle.)
template <int N>
double turn_angle(const Mat<N>& q, const Mat<N>& p) {
  return std::sqrt(std::max(N - q.cwiseProduct(p).sum(), 0.0));
}

}  // namespace

template <int N>
bool recycle_manifold(Pair<N>& p, const Body<N>& a, const Body<N>& b, const Mat<N>& ra, const Mat<N>& rb,
                      double extent, const ContactSettings& settings) {
  if (!p.cached || p.manifold.count == 0 || !(settings.recycle_distance > 0.0)) return false;
  if (turn_angle<N>(ra, p.rotation_a) > settings.recycle_angle ||
      turn_angle<N>(rb, p.rotation_b) > settings.recycle_angle)
    return false;
  // The turns since: dqa = ra Ra^T, dqb = rb Rb^T. The relative turn (b's in a's frame, then and now)
  // is (Ra^T Rb)^T (ra^T rb), whose trace is that of dqa^T dqb.
  const Mat<N> dqa = ra * p.rotation_a.transpose(), dqb = rb * p.rotation_b.transpose();
  const Vec<N> dc = b.center - a.center;
  const double moved = (ra.transpose() * dc - p.relative_position).norm();
  const double turned = turn_angle<N>(dqa, dqb);
  if (!(moved + extent * turned < settings.recycle_distance)) return false;
  Manifold<N>& m = p.manifold;
  m.depth = -INFINITY;
  for (int k = 0; k < m.count; ++k) {
    const Vec<N> on_a = dqa * p.anchor_a[k], on_b = dqb * p.anchor_b[k];  // the attached points now
    const double gap = p.base_gap[k] + m.normal.dot(dc + on_b - on_a);
    m.points[k].depth = -gap;
    m.points[k].point = 0.5 * (a.center + on_a + b.center + on_b);
    m.depth = std::max(m.depth, -gap);
  }
  m.intersecting = m.depth >= 0.0;
  return true;
}

template <int N>
void cache_manifold(Pair<N>& p, const Body<N>& a, const Body<N>& b, const Mat<N>& ra, const Mat<N>& rb) {
  p.cached = true;
  p.rotation_a = ra;
  p.rotation_b = rb;
  p.relative_position = ra.transpose() * (b.center - a.center);
  for (int k = 0; k < p.manifold.count; ++k) {
    const ContactPoint<N>& cp = p.manifold.points[k];
    p.arm_a[k] = p.anchor_a[k] = cp.point - a.center;
    p.arm_b[k] = p.anchor_b[k] = cp.point - b.center;
    p.base_gap[k] = -cp.depth;
  }
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template bool recycle_manifold<N>(Pair<N>&, const Body<N>&, const Body<N>&, const Mat<N>&, const Mat<N>&,   \
                                    double, const ContactSettings&);                                          \
  template void cache_manifold<N>(Pair<N>&, const Body<N>&, const Body<N>&, const Mat<N>&, const Mat<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
