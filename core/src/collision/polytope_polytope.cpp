// Polytope against polytope (boxes and meshes included, through their face lattices): the general
// separating axis test of paper section 7.2. The candidate axes are the facet normals of both shapes and,
// for k = 1..N-2, the normals of the span of a k-face direction space of a with an (N-1-k)-face direction
// space of b. These are exactly the facet normals of the Minkowski difference, so the smallest overlap
// over them is the exact minimum translation distance.
#include <cmath>
#include <limits>

#include "collision/narrow.hpp"
#include "linalg/decompositions.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {
namespace {

template <int N>
void min_max(const std::vector<Vec<N>>& v, const Vec<N>& u, double& lo, double& hi) {
  lo = hi = v[0].dot(u);
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double t = v[i].dot(u);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
}

}  // namespace

template <int N>
void sat_manifold(const ConvexFeatures<N>& fa, const Transform<N>& ta, const ConvexFeatures<N>& fb,
                  const Transform<N>& tb, const SatAxis<N>& best, double margin, Manifold<N>& m) {
  const double scale = std::max(fa.radius, fb.radius);
  {
    thread_local std::vector<ClipPoint<N>> incident;
    thread_local std::vector<Vec<N>> side_n;
    thread_local std::vector<double> side_o;
    thread_local std::vector<ContactPoint<N>> points;
    points.clear();
    if (best.facet_a >= 0 || best.facet_b >= 0) {
      const bool ref_a = best.facet_a >= 0;
      const ConvexFeatures<N>& fr = ref_a ? fa : fb;
      const ConvexFeatures<N>& fi = ref_a ? fb : fa;
      const Transform<N>& tr = ref_a ? ta : tb;
      const Transform<N>& ti = ref_a ? tb : ta;
      const int ref = ref_a ? best.facet_a : best.facet_b;
      const Vec<N> ref_n = tr.rotation * fr.facets[ref].normal;
      int inc = 0;  // the incident facet: the most anti-parallel to the reference normal
      double most = std::numeric_limits<double>::infinity();
      for (int g = 0; g < int(fi.facets.size()); ++g) {
        const double c = (ti.rotation * fi.facets[g].normal).dot(ref_n);
        if (c < most - 1e-12) most = c, inc = g;
      }
      facet_clip_points(fi, inc, ti, incident);
      facet_side_planes(fr, ref, tr, side_n, side_o);
      const std::uint64_t id = mix_id(mix_id(ref_a ? 1 : 2, std::uint64_t(ref)), std::uint64_t(inc));
      face_contact<N>(incident, side_n, side_o, ref_n, fr.facets[ref].offset + ref_n.dot(tr.position), margin, scale,
                      id, points);
    } else {
      // Mixed axis: one point, where the supporting features of a and b (along +normal and -normal)
      // come closest; found by least squares over their spans and the normal.
      const Vec<N>& u = best.normal;
      double lo, hi, lo2, hi2;
      thread_local std::vector<Vec<N>> va, vb;
      va.clear();
      vb.clear();
      for (const Vec<N>& v : fa.vertices) va.push_back(ta.apply(v));
      for (const Vec<N>& v : fb.vertices) vb.push_back(tb.apply(v));
      min_max(va, u, lo, hi);
      min_max(vb, u, lo2, hi2);
      const double tol = 1e-7 * scale;
      thread_local std::vector<int> sa, sb;
      sa.clear();
      sb.clear();
      for (int i = 0; i < int(va.size()); ++i)
        if (va[i].dot(u) >= hi - tol) sa.push_back(i);
      for (int i = 0; i < int(vb.size()); ++i)
        if (vb[i].dot(u) <= lo2 + tol) sb.push_back(i);
      // An orthonormal basis of each feature's directions (greedy Gram-Schmidt over its edges from the
      // first vertex, within the feature only); with u at most N columns, so the solve needs no heap.
      Eigen::Matrix<double, N, Eigen::Dynamic, 0, N, N> sys(N, 0);
      auto add_span = [&](const std::vector<Vec<N>>& w, const std::vector<int>& set, double sign) {
        const Eigen::Index first = sys.cols();
        for (std::size_t i = 1; i < set.size() && sys.cols() < N - 1; ++i) {
          Vec<N> e = sign * (w[set[i]] - w[set[0]]);
          for (Eigen::Index c = first; c < sys.cols(); ++c) e -= e.dot(sys.col(c)) * sys.col(c);
          const double len = e.norm();
          if (len <= 1e-9 * scale) continue;
          sys.conservativeResize(N, sys.cols() + 1);
          sys.col(sys.cols() - 1) = e / len;
        }
      };
      add_span(va, sa, 1.0);
      const Eigen::Index from_a = sys.cols();
      add_span(vb, sb, -1.0);
      sys.conservativeResize(N, sys.cols() + 1);
      sys.col(sys.cols() - 1) = -u;
      // pa + sum x_i (a's directions) = pb + sum y_j (b's directions) + delta u. Nearly parallel
      // features make the system nearly singular: a rank-revealing solve drops the dependent
      // directions (their coefficients are 0) instead of sending the point metres away.
      const linalg::SmallVector x = linalg::solve_rank_revealing(sys, Vec<N>(vb[sb[0]] - va[sa[0]]), 1e-6);
      Vec<N> pa = va[sa[0]];
      for (Eigen::Index i = 0; i < from_a; ++i) pa += x[i] * sys.col(i);
      // pa should lie on a, and pa - pen u on b. Where the closest approach of the features' spans
      // falls beyond either feature (nearly parallel features), take the centre of the features'
      // overlap instead: the mean of the vertices of each feature that lie within the other body.
      auto inside = [&](const ConvexFeatures<N>& f, const Transform<N>& t, const Vec<N>& p) {
        const Vec<N> local = t.rotation.transpose() * (p - t.position);
        for (const auto& facet : f.facets)
          if (!(facet.normal.dot(local) - facet.offset <= 1e-6 * scale)) return false;
        return true;
      };
      if (!inside(fa, ta, pa) || !inside(fb, tb, Vec<N>(pa - best.pen * u))) {
        Vec<N> sum = Vec<N>::Zero(), ca = Vec<N>::Zero(), cb = Vec<N>::Zero();
        int count = 0;
        for (int i : sa) {
          ca += va[i];
          if (inside(fb, tb, Vec<N>(va[i] - best.pen * u))) sum += va[i], ++count;
        }
        for (int i : sb) {
          cb += vb[i];
          if (inside(fa, ta, Vec<N>(vb[i] + best.pen * u))) sum += vb[i] + best.pen * u, ++count;
        }
        pa = count > 0 ? Vec<N>(sum / double(count))
                       : Vec<N>(0.5 * (ca / double(sa.size()) + cb / double(sb.size())) + 0.5 * best.pen * u);
      }
      std::uint64_t id = 3;
      for (int i : sa) id = mix_id(id, std::uint64_t(i));
      for (int i : sb) id = mix_id(id, std::uint64_t(i) << 32);
      if (best.pen >= -margin) points.push_back({Vec<N>(pa - 0.5 * best.pen * u), best.pen, id});
    }
    reduce_into(points, m);
  }

}

template <int N>
Manifold<N> polytope_polytope(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb,
                              const CollisionSettings& settings) {
  const ConvexFeatures<N>& fa = *a.features();
  const ConvexFeatures<N>& fb = *b.features();
  thread_local std::vector<Vec<N>> va, vb;
  va.clear();
  vb.clear();
  for (const Vec<N>& v : fa.vertices) va.push_back(ta.apply(v));
  for (const Vec<N>& v : fb.vertices) vb.push_back(tb.apply(v));
  const double scale = std::max(fa.radius, fb.radius);
  // Ties within this go to the earlier candidate: a's faces, then b's, then mixed axes, so that a
  // resting contact keeps its face-to-face manifold (relative 1e-9 of the size: round-off level).
  // A gap within the same band is touching, not apart.
  const double tie = round_off_band(scale);
  const double margin = settings.contact_margin;

  SatAxis<N> best, sep;
  Manifold<N> m;
  // `slack`: how much shallower than the best so far the axis must be (face preference, mixed axes).
  auto consider = [&](const SatAxis<N>& c, double slack = 0.0) {
    if (c.pen < best.pen - tie - slack) best = c;
    if (c.pen >= -margin - tie) return true;
    sep = c;  // separated beyond the margin: stop early
    return false;
  };

  double lo, hi, lo2, hi2;
  for (int f = 0; f < int(fa.facets.size()); ++f) {
    const Vec<N> n = ta.rotation * fa.facets[f].normal;
    min_max(vb, n, lo, hi);
    if (!consider({fa.facets[f].offset + n.dot(ta.position) - lo, n, f, -1})) goto separated;
  }
  for (int g = 0; g < int(fb.facets.size()); ++g) {
    const Vec<N> n = tb.rotation * fb.facets[g].normal;  // outward of b: the a -> b normal is -n
    min_max(va, n, lo, hi);
    if (!consider({fb.facets[g].offset + n.dot(tb.position) - lo, Vec<N>(-n), -1, g})) goto separated;
  }
  for (int k = 1; k <= N - 2; ++k)
    for (const auto& da : fa.directions[k])
      for (const auto& db : fb.directions[N - 1 - k]) {
        Eigen::Matrix<double, N, N - 1> span;
        for (int i = 0; i < k; ++i) span.col(i) = ta.rotation * da.basis[i];
        for (int i = 0; i < N - 1 - k; ++i) span.col(k + i) = tb.rotation * db.basis[i];
        const Vec<N> u = orthogonal_complement<N>(span, 1e-6);
        if (u.isZero()) continue;  // parallel features: the face axes cover this direction
        min_max(va, u, lo, hi);
        min_max(vb, u, lo2, hi2);
        const double up = hi - lo2, down = hi2 - lo;  // overlap with b above a along u, and below
        if (!consider(up <= down ? SatAxis<N>{up, u, -1, -1} : SatAxis<N>{down, Vec<N>(-u), -1, -1},
                      settings.face_preference))
          goto separated;
      }

  m.intersecting = best.pen >= 0.0;
  m.depth = best.pen;
  m.normal = best.normal;
  sat_manifold(fa, ta, fb, tb, best, margin + tie, m);
  return m;

separated:  // minus the gap along the separating axis: a lower bound the dispatcher may refine
  m.intersecting = false;
  m.depth = sep.pen;
  m.normal = sep.normal;
  return m;
}

#define WEDGE_INSTANTIATE(N)                                                                               \
  template void sat_manifold<N>(const ConvexFeatures<N>&, const Transform<N>&, const ConvexFeatures<N>&,   \
                                const Transform<N>&, const SatAxis<N>&, double, Manifold<N>&);             \
  template Manifold<N> polytope_polytope<N>(const Shape<N>&, const Transform<N>&, const Shape<N>&, \
                                            const Transform<N>&, const CollisionSettings&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
