// EPA, the expanding polytope algorithm (van den Bergen 2001), in any dimension N: the penetration depth
// and direction of two overlapping convex sets from their support functions, starting from the simplex
// with which gjk() proved the overlap.
//
//   1. Blow-up: while the simplex has fewer than N + 1 points, query the support of A - B both ways
//      along a direction orthogonal to its affine hull and keep the farther point. The origin stays in
//      the simplex (on its boundary, perhaps), and the simplex stays full-dimensional. If A - B has no
//      extent across that direction it is flat through the origin: depth 0 along it, exactly.
//   2. Expansion: the polytope's boundary is a list of facets, (N-1)-simplices of N vertex indices with
//      outward unit normal and signed distance from the origin (outward = away from the centroid of the
//      starting simplex, which stays interior). Take the closest facet, query the support in its normal;
//      if that gains less than the tolerance, the facet's distance is the depth. Otherwise remove every
//      facet that sees the new point and stitch the hole: the horizon ridges are the (N-2)-faces (N-1
//      vertex indices, kept sorted as keys) that belong to exactly one removed facet; each gives a new
//      facet ridge + new point. In 2D facets are segments and ridges single vertices, with the same code.
//
// Deterministic: facets are kept in creation order, ridges are matched by sorting their keys, ties go to
// the lowest index; no unordered containers. Storage lives in an EpaWorkspace that can be reused, so
// that repeated calls do not allocate once the workspace has grown.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "wedge/collision/detail/gjk.hpp"

namespace wedge {

struct EpaSettings {
  int max_iterations = 128;
  // Stop when the support in the closest facet's normal lies within tolerance * scale of the facet,
  // where scale is the size of A - B (the largest |w| of the starting simplex and the blow-up points).
  // The facet's distance is a lower bound of the depth and the support an upper bound, so on success
  // the depth is exact to tolerance * scale. Polytopes stop exactly (the support repeats a vertex);
  // round shapes converge linearly and may need a looser tolerance or more iterations.
  double tolerance = 1e-10;
  // Storage cap (a 6D ball needs ~1e5 facets for 1000 iterations); reaching it ends the run, ok = false.
  int max_facets = 200000;
};

template <int N>
struct EpaResult {
  // Converged to the tolerance. When false (iteration cap) the other fields still hold the best answer
  // found: a depth that is a lower bound, and a valid unit normal.
  bool ok = false;
  // >= 0: translating B by depth * normal (or A by -depth * normal) makes A and B touch.
  double depth = 0.0;
  // Unit, from A to B: the outward normal of A - B at its boundary point nearest the origin.
  Vec<N> normal = Vec<N>::Unit(0);
  // The deepest points: point_a on A's surface (extreme along normal), point_b on B's (extreme along
  // -normal), point_a - point_b = depth * normal.
  Vec<N> point_a = Vec<N>::Zero(), point_b = Vec<N>::Zero();
  int iterations = 0;
};

template <int N>
struct EpaWorkspace {
  struct Facet {
    std::array<int, N> v;  // vertex indices
    Vec<N> normal;         // outward unit normal
    double distance;       // normal . (any vertex); the origin's distance to the plane, signed
  };
  std::vector<Vec<N>> w, a, b;
  std::vector<Facet> facets;
  std::vector<std::array<int, N - 1>> ridges;
};

namespace detail {

// Barycentric round-off allowed when deciding that a facet holds the origin's projection.
inline constexpr double kHoldsProjection = 1e-12;
// Facets whose unit normals and distances (relative to the size of A - B) agree to this are coplanar:
// round-off in normals computed from different O(1) vertex triples is ~1e-15.
inline constexpr double kCoplanar = 1e-10;

// The outward plane of the facet through p[0..N): false if the points are affinely dependent.
template <int N>
bool facet_plane(const Vec<N>* const* p, const Vec<N>& interior, Vec<N>& normal, double& distance) {
  std::array<Vec<N>, N - 1> q;
  double longest2 = 0.0;
  for (int j = 0; j < N - 1; ++j) {
    q[j] = *p[j + 1] - *p[0];
    longest2 = std::max(longest2, q[j].squaredNorm());
  }
  const double threshold = kAffineDegenerate * std::sqrt(longest2);
  for (int j = 0; j < N - 1; ++j) {
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i < j; ++i) q[j] -= q[i].dot(q[j]) * q[i];
    const double len = q[j].norm();
    if (!(len > threshold)) return false;
    q[j] /= len;
  }
  // The normal: the coordinate axis least covered by the edges' span, minus its projection on it. The
  // squared residuals of the N axes sum to 1, so the chosen one is at least 1/sqrt(N) long.
  int axis = 0;
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < N; ++k) {
    double covered = 0.0;
    for (int j = 0; j < N - 1; ++j) covered += q[j][k] * q[j][k];
    if (covered < least) {
      least = covered;
      axis = k;
    }
  }
  normal = Vec<N>::Unit(axis);
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < N - 1; ++j) normal -= q[j].dot(normal) * q[j];
  normal.normalize();
  distance = normal.dot(*p[0]);
  if (distance < normal.dot(interior)) {
    normal = -normal;
    distance = -distance;
  }
  return true;
}

// point_a, point_b: the barycentric combination of the witnesses for the origin's projection onto the
// affine hull of the vertices idx[0..count) (coordinates clamped to >= 0 against round-off).
template <int N>
void epa_witnesses(const EpaWorkspace<N>& ws, const int* idx, int count, EpaResult<N>& res) {
  const Vec<N>* p[N + 1] = {};
  for (int i = 0; i < count; ++i) p[i] = &ws.w[idx[i]];
  double lambda[N + 1];
  if (!affine_closest<N>(p, count, lambda))
    for (int i = 0; i < count; ++i) lambda[i] = 1.0 / count;
  double sum = 0.0;
  for (int i = 0; i < count; ++i) sum += (lambda[i] = std::max(lambda[i], 0.0));
  res.point_a = Vec<N>::Zero();
  res.point_b = Vec<N>::Zero();
  for (int i = 0; i < count; ++i) {
    res.point_a += (lambda[i] / sum) * ws.a[idx[i]];
    res.point_b += (lambda[i] / sum) * ws.b[idx[i]];
  }
}

}  // namespace detail

// EPA from the simplex of an intersecting gjk() result (precondition: the origin is in, or within GJK's
// tolerance of, conv(start)); start.size == 0 is allowed (a first point is queried along e0).
template <int N, class SupportA, class SupportB>
EpaResult<N> epa(const SupportA& support_a, const SupportB& support_b, const Simplex<N>& start,
                 const EpaSettings& settings, EpaWorkspace<N>& ws) {
  EpaResult<N> res;
  ws.w.clear();
  ws.a.clear();
  ws.b.clear();
  ws.facets.clear();
  const auto add = [&](const Vec<N>& pa, const Vec<N>& pb) {
    ws.a.push_back(pa);
    ws.b.push_back(pb);
    ws.w.push_back(pa - pb);
  };
  const auto support = [&](const Vec<N>& d, Vec<N>& pa, Vec<N>& pb) {
    pa = support_a(d);
    pb = support_b(Vec<N>(-d));
  };
  double scale = 0.0;
  // Copy the start, dropping points that are affinely dependent on the ones kept.
  for (int i = 0; i < start.size; ++i) {
    add(start.a[i], start.b[i]);
    const int count = int(ws.w.size());
    const Vec<N>* p[N + 1] = {};
    for (int j = 0; j < count; ++j) p[j] = &ws.w[j];
    double lambda[N + 1];
    if (count > 1 && !detail::affine_closest<N>(p, count, lambda)) {
      ws.w.pop_back();
      ws.a.pop_back();
      ws.b.pop_back();
      continue;
    }
    scale = std::max(scale, ws.w.back().norm());
  }
  if (ws.w.empty()) {
    Vec<N> pa, pb;
    support(Vec<N>::Unit(0), pa, pb);
    add(pa, pb);
    scale = ws.w.back().norm();
  }

  // 1. Blow-up to a full simplex.
  while (int(ws.w.size()) < N + 1) {
    const int count = int(ws.w.size());
    std::array<Vec<N>, N> q;
    for (int j = 0; j + 1 < count; ++j) {
      q[j] = ws.w[j + 1] - ws.w[0];
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < j; ++i) q[j] -= q[i].dot(q[j]) * q[i];
      q[j].normalize();  // independent: checked when the point was added
    }
    int axis = 0;
    double least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < N; ++k) {
      double covered = 0.0;
      for (int j = 0; j + 1 < count; ++j) covered += q[j][k] * q[j][k];
      if (covered < least) {
        least = covered;
        axis = k;
      }
    }
    Vec<N> d = Vec<N>::Unit(axis);
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j + 1 < count; ++j) d -= q[j].dot(d) * q[j];
    d.normalize();
    Vec<N> pa_plus, pb_plus, pa_minus, pb_minus;
    support(d, pa_plus, pb_plus);
    support(Vec<N>(-d), pa_minus, pb_minus);
    const Vec<N> w_plus = pa_plus - pb_plus, w_minus = pa_minus - pb_minus;
    scale = std::max({scale, w_plus.norm(), w_minus.norm()});
    const double h_plus = d.dot(w_plus - ws.w[0]), h_minus = -d.dot(w_minus - ws.w[0]);
    if (!(std::max(h_plus, h_minus) > settings.tolerance * scale)) {
      // A - B is flat across d and contains the origin: it has no interior, the depth is 0 along d.
      res.ok = true;
      res.normal = d;
      std::array<int, N + 1> idx;
      for (int i = 0; i < count; ++i) idx[i] = i;
      detail::epa_witnesses<N>(ws, idx.data(), count, res);
      return res;
    }
    if (h_plus >= h_minus)
      add(pa_plus, pb_plus);
    else
      add(pa_minus, pb_minus);
  }

  // 2. Expansion. The centroid of the starting simplex is interior to every later polytope.
  Vec<N> interior = Vec<N>::Zero();
  for (const Vec<N>& p : ws.w) interior += p;
  interior /= double(N + 1);
  const double tol_abs = settings.tolerance * scale;
  // A facet is removed when the new point is beyond its plane by more than visible_eps: every new facet
  // is then non-degenerate (its apex is that far off the ridge's facet plane, 1e-3 above the flatness
  // threshold), and the polytope stays convex to that (a larger value lets round shapes grow concave
  // and then fold over). The closest facet, which the point passes by more than the tolerance, is
  // always removed.
  const double visible_eps = std::min(0.5 * tol_abs, 1e3 * detail::kAffineDegenerate * scale);
  const auto make_facet = [&](const std::array<int, N>& v) {
    typename EpaWorkspace<N>::Facet f{v, Vec<N>::Unit(0), 0.0};
    const Vec<N>* p[N] = {};
    for (int i = 0; i < N; ++i) p[i] = &ws.w[v[i]];
    // A degenerate facet (not expected, see visible_eps) keeps the hull closed but is never chosen.
    if (!detail::facet_plane<N>(p, interior, f.normal, f.distance))
      f.distance = std::numeric_limits<double>::infinity();
    ws.facets.push_back(f);
  };
  for (int skip = 0; skip <= N; ++skip) {
    std::array<int, N> v;
    for (int i = 0, n = 0; i <= N; ++i)
      if (i != skip) v[n++] = i;
    make_facet(v);
  }

  int closest = 0;
  // In exact arithmetic the closest distance never decreases. If round-off folds the polytope over
  // (seen with round shapes in 5D/6D) it does: the run stops there with the last sound facet.
  typename EpaWorkspace<N>::Facet last_sound = ws.facets[0];
  bool broken = false;
  while (true) {
    closest = 0;
    for (int f = 1; f < int(ws.facets.size()); ++f)
      if (ws.facets[f].distance < ws.facets[closest].distance) closest = f;
    const typename EpaWorkspace<N>::Facet& fc = ws.facets[closest];
    if (!std::isfinite(fc.distance)) break;  // only degenerate facets left (not expected)
    if (res.iterations > 0 && fc.distance < last_sound.distance - tol_abs) {
      broken = true;
      break;
    }
    last_sound = fc;
    if (res.iterations >= settings.max_iterations || int(ws.facets.size()) > settings.max_facets) break;
    ++res.iterations;
    Vec<N> pa, pb;
    support(fc.normal, pa, pb);
    const Vec<N> w = pa - pb;
    if (!all_finite(w)) break;
    if (fc.normal.dot(w) - fc.distance <= tol_abs) {
      res.ok = true;
      break;
    }
    add(pa, pb);
    const int apex = int(ws.w.size()) - 1;
    // Remove the facets that see the new point, collecting their ridges; compact in order.
    ws.ridges.clear();
    int kept = 0;
    for (int f = 0; f < int(ws.facets.size()); ++f) {
      const typename EpaWorkspace<N>::Facet& g = ws.facets[f];
      const bool visible = f == closest || (std::isfinite(g.distance) && g.normal.dot(w) - g.distance > visible_eps);
      if (!visible) {
        ws.facets[kept++] = g;
        continue;
      }
      for (int drop = 0; drop < N; ++drop) {
        std::array<int, N - 1> key;
        for (int i = 0, n = 0; i < N; ++i)
          if (i != drop) key[n++] = g.v[i];
        std::sort(key.begin(), key.end());
        ws.ridges.push_back(key);
      }
    }
    ws.facets.resize(kept);
    // Horizon: ridges of exactly one removed facet (interior ridges appear twice).
    std::sort(ws.ridges.begin(), ws.ridges.end());
    for (std::size_t r = 0; r < ws.ridges.size();) {
      std::size_t e = r + 1;
      while (e < ws.ridges.size() && ws.ridges[e] == ws.ridges[r]) ++e;
      if (e - r == 1) {
        std::array<int, N> v;
        for (int i = 0; i < N - 1; ++i) v[i] = ws.ridges[r][i];
        v[N - 1] = apex;
        make_facet(v);
      }
      r = e;
    }
    if (ws.facets.empty()) break;  // not expected: a closed hull always has a horizon
  }

  if (broken) {
    res.ok = false;
    res.depth = std::max(last_sound.distance, 0.0);
    res.normal = last_sound.normal;
    detail::epa_witnesses<N>(ws, last_sound.v.data(), N, res);
    return res;
  }
  if (ws.facets.empty() || !std::isfinite(ws.facets[closest].distance)) {
    // Broken polytope (round-off on degenerate input): the best we can say is "touching".
    res.ok = false;
    return res;
  }
  // The nearest face of A - B may be tiled by several coplanar facets (always for box faces), and the
  // closest one need not hold the origin's projection: take the first coplanar one (same plane to
  // kCoplanar) that does, so that point_a - point_b = depth * normal.
  int chosen = -1;
  const Vec<N> n_closest = ws.facets[closest].normal;
  const double d_closest = ws.facets[closest].distance;
  for (int f = 0; f < int(ws.facets.size()); ++f) {
    const typename EpaWorkspace<N>::Facet& g = ws.facets[f];
    if (!((g.normal - n_closest).norm() <= detail::kCoplanar && std::abs(g.distance - d_closest) <= detail::kCoplanar * scale))
      continue;
    const Vec<N>* p[N] = {};
    for (int i = 0; i < N; ++i) p[i] = &ws.w[g.v[i]];
    double lambda[N];
    if (!detail::affine_closest<N>(p, N, lambda)) continue;
    bool holds = true;
    for (int i = 0; i < N; ++i) holds = holds && lambda[i] >= -detail::kHoldsProjection;
    if (holds) {
      chosen = f;
      break;
    }
  }
  if (chosen < 0) {
    // No facet holds the projection: round-off has made the polytope non-convex there (seen with
    // round shapes from 5D on). Depth and normal are still the closest facet's; the witnesses are
    // clamped to it and do not satisfy point_a - point_b = depth * normal, so report ok = false.
    res.ok = false;
    chosen = closest;
  }
  const typename EpaWorkspace<N>::Facet& fc = ws.facets[chosen];
  res.depth = std::max(fc.distance, 0.0);
  res.normal = fc.normal;
  detail::epa_witnesses<N>(ws, fc.v.data(), N, res);
  return res;
}

template <int N, class SupportA, class SupportB>
EpaResult<N> epa(const SupportA& support_a, const SupportB& support_b, const Simplex<N>& start,
                 const EpaSettings& settings = {}) {
  EpaWorkspace<N> ws;
  return epa<N>(support_a, support_b, start, settings, ws);
}

}  // namespace wedge
