// GJK (Gilbert, Johnson & Keerthi 1988) in any dimension N: distance, closest points and intersection
// of two convex sets A and B given only by their support functions. GJK walks the Minkowski difference
// A - B = {a - b} towards the origin with simplices of at most N + 1 points; nothing in it depends on N
// except the closest-point sub-algorithm, which here is the signed-volumes method of Montanari, Sommer
// & Gerbaudo (2017) generalised to a k-simplex in R^N (see docs/architecture.md, "GJK and EPA"):
//
//   * the barycentric coordinates of the origin's projection onto the simplex's affine hull are the
//     ratios C_j / D of signed volumes; they are computed in an orthonormal frame of that hull (modified
//     Gram-Schmidt run twice on the edges, then back substitution), never through the Gram matrix, so
//     the conditioning is that of the edges, not its square;
//   * if every coordinate is positive the projection is the answer; otherwise only the faces opposite
//     the non-positive coordinates can hold the closest point, and they are searched recursively
//     (each subset at most once: 2^(N+1) - 1 <= 127 subsets in 6D), keeping the nearest candidate;
//   * an affinely dependent (flat) simplex is never solved: all of its faces are searched instead, which
//     is exact because a flat simplex is the union of its facets.
//
// Header-only templates on the support callables, so that they inline. No heap, no NaN for finite
// support points.
#pragma once

#include <algorithm>
#include <array>
#include <bitset>
#include <cmath>
#include <limits>

#include "wedge/ga/types.hpp"

namespace wedge {

// A support function of a convex set C is a callable Vec<N>(const Vec<N>& d) returning a point of C
// that is extreme in direction d (world frame; d need not have unit length, and is never zero when GJK
// or EPA call it with a finite non-degenerate input). It must return finite points.

template <int N>
struct GjkSettings {
  int max_iterations = 64;
  // Relative accuracy of the distance: GJK stops when the gap between the upper bound |v| and the lower
  // bound v.w/|v| is at most tolerance * |v|, i.e. |v|^2 - v.w <= tolerance |v|^2 (the classic test
  // |v|^2 - v.w <= eps^2 |v|^2 with eps^2 = tolerance). A distance below tolerance times the size of
  // A - B (the largest |w| seen) counts as touching: intersecting.
  double tolerance = 1e-10;
};

// Points w = a - b of A - B with their witnesses a in A and b in B, in slots 0..size-1.
template <int N>
struct Simplex {
  std::array<Vec<N>, N + 1> w, a, b;
  int size = 0;
};

template <int N>
struct GjkResult {
  // The origin lies inside or on A - B, up to the touching tolerance.
  bool intersecting = false;
  // |point_a - point_b| >= 0; exactly 0 when intersecting.
  double distance = 0.0;
  // Closest points (world frame) when separated; when intersecting a point common to A and B up to the
  // tolerance (point_a ~ point_b).
  Vec<N> point_a = Vec<N>::Zero(), point_b = Vec<N>::Zero();
  // The final simplex; when intersecting it contains the origin (or touches it), ready for epa().
  Simplex<N> simplex;
  int iterations = 0;
};

namespace detail {

// Relative size below which an edge counts as dependent on the previous ones (sine of the angle to
// their span, times their length relative to the longest edge). Flat simplices are not solved: their
// faces are (see above), so the value only decides between two exact paths; 1e-12 keeps the back
// substitution's division well away from round-off (relative error of the coordinates <= ~1e-4 at the
// threshold, and only along the nearly dependent direction, which barely moves the point).
inline constexpr double kAffineDegenerate = 1e-12;

// Barycentric coordinates lambda[0..count) (summing to 1) of the point of the affine hull of p[0..count)
// nearest to the origin. Returns false (lambda unset) if the points are affinely dependent.
template <int N>
bool affine_closest(const Vec<N>* const* p, int count, double* lambda) {
  if (count < 1 || count > N + 1) return false;
  const int k = count - 1;
  if (k == 0) {
    lambda[0] = 1.0;
    return true;
  }
  std::array<Vec<N>, N> q;
  double r[N][N] = {};
  double longest2 = 0.0;
  for (int j = 0; j < k; ++j) {
    q[j] = *p[j + 1] - *p[0];
    longest2 = std::max(longest2, q[j].squaredNorm());
  }
  const double threshold = kAffineDegenerate * std::sqrt(longest2);
  for (int j = 0; j < k; ++j) {
    for (int pass = 0; pass < 2; ++pass)  // "twice is enough" (Kahan, Parlett)
      for (int i = 0; i < j; ++i) {
        const double c = q[i].dot(q[j]);
        r[i][j] += c;
        q[j] -= c * q[i];
      }
    const double len = q[j].norm();
    if (!(len > threshold)) return false;  // also catches NaN
    r[j][j] = len;
    q[j] /= len;
  }
  // p0 + E mu nearest to the origin: E = Q R, so R mu = -Q^T p0.
  double mu[N] = {};
  double sum = 0.0;
  for (int i = k - 1; i >= 0; --i) {
    double y = -q[i].dot(*p[0]);
    for (int j = i + 1; j < k; ++j) y -= r[i][j] * mu[j];
    mu[i] = y / r[i][i];
    sum += mu[i];
  }
  lambda[0] = 1.0 - sum;
  for (int i = 0; i < k; ++i) lambda[i + 1] = mu[i];
  return true;
}

template <int N>
struct SimplexClosest {
  double dist2 = std::numeric_limits<double>::infinity();
  unsigned mask = 0;                  // the slots of the face holding the closest point
  std::array<double, N + 1> lambda{};  // its barycentric coordinates, by slot (0 outside mask)
};

template <int N>
void simplex_closest_rec(const std::array<Vec<N>, N + 1>& w, unsigned mask, std::bitset<(1u << (N + 1))>& visited,
                         SimplexClosest<N>& best) {
  if (visited[mask]) return;
  visited[mask] = true;
  int slot[N + 1];
  const Vec<N>* p[N + 1] = {};
  int count = 0;
  for (int i = 0; i <= N; ++i)
    if (mask & (1u << i)) {
      slot[count] = i;
      p[count++] = &w[i];
    }
  double lambda[N + 1];
  const bool solved = affine_closest<N>(p, count, lambda);
  bool inside = solved;
  for (int c = 0; c < count && inside; ++c) inside = lambda[c] > 0.0;
  if (inside) {
    Vec<N> v = lambda[0] * *p[0];
    for (int c = 1; c < count; ++c) v += lambda[c] * *p[c];
    const double d2 = v.squaredNorm();
    if (d2 < best.dist2) {  // strict: the first candidate found wins ties (deterministic)
      best.dist2 = d2;
      best.mask = mask;
      best.lambda.fill(0.0);
      for (int c = 0; c < count; ++c) best.lambda[slot[c]] = lambda[c];
    }
    return;
  }
  // Outside (or flat): the closest point lies on a face opposite a non-positive coordinate (any face
  // when flat). count >= 2 here: a single point is always solved and inside.
  for (int c = 0; c < count; ++c)
    if (!solved || !(lambda[c] > 0.0)) simplex_closest_rec<N>(w, mask & ~(1u << slot[c]), visited, best);
}

// The point of conv(w[slots in mask]) nearest to the origin.
template <int N>
SimplexClosest<N> simplex_closest(const std::array<Vec<N>, N + 1>& w, unsigned mask) {
  std::bitset<(1u << (N + 1))> visited;
  SimplexClosest<N> best;
  simplex_closest_rec<N>(w, mask, visited, best);
  return best;
}

}  // namespace detail

// GJK on A - B. initial_direction is the first search direction, from A towards B (a good choice is
// centre_b - centre_a; zero or non-finite falls back to e0). Works for any finite support functions,
// including points, segments and other flat sets.
template <int N, class SupportA, class SupportB>
GjkResult<N> gjk(const SupportA& support_a, const SupportB& support_b, const Vec<N>& initial_direction,
                 const GjkSettings<N>& settings = {}) {
  GjkResult<N> res;
  Simplex<N>& s = res.simplex;
  Vec<N> d = initial_direction;
  if (!all_finite(d) || !(d.squaredNorm() > 0.0)) d = Vec<N>::Unit(0);
  // v (the current closest point of A - B) starts as the support point of A - B in direction d, i.e.
  // sA(d) - sB(-d), the point nearest the origin if d is the true direction from A to B; every later
  // query is in -v.
  s.a[0] = support_a(d);
  s.b[0] = support_b(Vec<N>(-d));
  s.w[0] = s.a[0] - s.b[0];
  s.size = 1;
  std::array<double, N + 1> lambda{};
  lambda[0] = 1.0;
  Vec<N> v = s.w[0];
  double v2 = v.squaredNorm();
  double scale2 = v2;  // the largest |w|^2 seen: the size of A - B as far as known
  const double tol = settings.tolerance;
  bool intersecting = false;
  while (true) {
    if (v2 <= tol * tol * scale2) {  // touching or overlapping, to tolerance
      intersecting = true;
      break;
    }
    if (res.iterations >= settings.max_iterations) break;
    ++res.iterations;
    const Vec<N> a = support_a(Vec<N>(-v));
    const Vec<N> b = support_b(v);
    const Vec<N> w = a - b;
    if (!all_finite(w)) break;  // a broken support function: keep the last finite answer
    scale2 = std::max(scale2, w.squaredNorm());
    // v.w / |v| is a lower bound of the distance, |v| an upper bound.
    if (v2 - v.dot(w) <= tol * v2) break;
    bool repeated = false;
    for (int i = 0; i < s.size; ++i) repeated = repeated || w == s.w[i];
    if (repeated) break;  // no new point: no progress possible
    const int added = s.size;
    s.w[added] = w;
    s.a[added] = a;
    s.b[added] = b;
    ++s.size;
    const detail::SimplexClosest<N> best = detail::simplex_closest<N>(s.w, (1u << s.size) - 1u);
    if (!(best.dist2 < v2)) {  // no progress (round-off): keep the previous simplex and v
      --s.size;
      break;
    }
    // Keep only the face holding the closest point, in slot order.
    int n = 0;
    for (int i = 0; i < s.size; ++i)
      if (best.mask & (1u << i)) {
        s.w[n] = s.w[i];
        s.a[n] = s.a[i];
        s.b[n] = s.b[i];
        lambda[n] = best.lambda[i];
        ++n;
      }
    s.size = n;
    v = lambda[0] * s.w[0];
    for (int i = 1; i < n; ++i) v += lambda[i] * s.w[i];
    v2 = v.squaredNorm();
    if (n == N + 1) {  // the origin is strictly inside a full simplex
      intersecting = true;
      break;
    }
  }
  res.point_a = lambda[0] * s.a[0];
  res.point_b = lambda[0] * s.b[0];
  for (int i = 1; i < s.size; ++i) {
    res.point_a += lambda[i] * s.a[i];
    res.point_b += lambda[i] * s.b[i];
  }
  res.intersecting = intersecting;
  res.distance = intersecting ? 0.0 : std::sqrt(v2);
  return res;
}

}  // namespace wedge
