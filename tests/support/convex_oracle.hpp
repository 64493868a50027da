// Support functions of test shapes (point sets, boxes, balls) and independent oracles for GJK/EPA tests:
// the Minkowski difference A - B of two polytopes is the convex hull of all a_i - b_j, built by Qhull
// (wedge::convex_hull). From its facets: the origin is inside iff every facet offset is positive, and
// then the penetration depth is the smallest offset and the normal that facet's (outward from A - B,
// i.e. from A towards B). The distance of an outside origin is found by brute force over every face of
// every boundary cell: the origin's projection onto the face's affine hull through the KKT system of
// min |P lambda|^2 subject to sum lambda = 1 (Eigen FullPivLU), kept when all lambda >= 0 - a different
// algorithm from the library's (orthonormalised edges, pruned recursion). For boxes there is also the
// exact separating-axis test (box_sat), fast enough for 6D where the 4096-point hull is slow.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "dense.hpp"
#include "wedge/ga/types.hpp"
#include "wedge/hull.hpp"

namespace oracle {

using wedge::Mat;
using wedge::Vec;

template <int N>
Vec<N> gaussian(std::mt19937_64& rng) {
  std::normal_distribution<double> nd;
  Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = nd(rng);
  return v;
}

template <int N>
Vec<N> unit(std::mt19937_64& rng) {
  return gaussian<N>(rng).normalized();
}

// A uniformly random rotation (QR of a Gaussian matrix with the signs fixed, then det = +1).
template <int N>
Mat<N> rotation(std::mt19937_64& rng) {
  Mat<N> g;
  for (int j = 0; j < N; ++j) g.col(j) = gaussian<N>(rng);
  return dense::haar_rotation(g);
}

// The convex hull of points, as a support function (the first maximiser wins ties).
template <int N>
struct PointsSupport {
  std::vector<Vec<N>> points;
  Vec<N> operator()(const Vec<N>& d) const {
    std::size_t best = 0;
    double h = points[0].dot(d);
    for (std::size_t i = 1; i < points.size(); ++i) {
      const double hi = points[i].dot(d);
      if (hi > h) {
        h = hi;
        best = i;
      }
    }
    return points[best];
  }
};

// n points uniformly in the ball of the given centre and radius (at least N + 1, in general position).
template <int N>
PointsSupport<N> random_polytope(std::mt19937_64& rng, int n, const Vec<N>& centre, double radius) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointsSupport<N> s;
  for (int i = 0; i < n; ++i) {
    const double r = radius * std::pow(u(rng), 1.0 / N);  // (two draws: one per statement, so that every
    s.points.push_back(centre + r * unit<N>(rng));        // compiler draws them in the same order)
  }
  return s;
}

// centre + R (h .* sign(R^T d)).
template <int N>
struct BoxSupport {
  Vec<N> centre = Vec<N>::Zero();
  Mat<N> rotation = Mat<N>::Identity();
  Vec<N> half = Vec<N>::Ones();
  Vec<N> operator()(const Vec<N>& d) const {
    const Vec<N> local = rotation.transpose() * d;
    Vec<N> p;
    for (int i = 0; i < N; ++i) p[i] = local[i] >= 0.0 ? half[i] : -half[i];
    return centre + rotation * p;
  }
  std::vector<Vec<N>> corners() const {
    std::vector<Vec<N>> c;
    for (int m = 0; m < (1 << N); ++m) {
      Vec<N> p;
      for (int i = 0; i < N; ++i) p[i] = (m >> i) & 1 ? half[i] : -half[i];
      c.push_back(centre + rotation * p);
    }
    return c;
  }
};

// A box with a random orientation and half extents in [0.2, 1.2].
template <int N>
BoxSupport<N> random_box(std::mt19937_64& rng, const Vec<N>& centre) {
  std::uniform_real_distribution<double> u(0.2, 1.2);
  BoxSupport<N> b;
  b.centre = centre;
  b.rotation = rotation<N>(rng);
  for (int i = 0; i < N; ++i) b.half[i] = u(rng);
  return b;
}

template <int N>
struct BallSupport {
  Vec<N> centre = Vec<N>::Zero();
  double radius = 1.0;
  Vec<N> operator()(const Vec<N>& d) const {
    const double n = d.norm();
    return n > 0.0 ? Vec<N>(centre + (radius / n) * d) : Vec<N>(centre + radius * Vec<N>::Unit(0));
  }
};

template <int N>
std::vector<Vec<N>> minkowski_difference(const std::vector<Vec<N>>& a, const std::vector<Vec<N>>& b) {
  std::vector<Vec<N>> m;
  for (const Vec<N>& p : a)
    for (const Vec<N>& q : b) m.push_back(p - q);
  return m;
}

// max over facets of n . x - offset: <= 0 iff x is in the hull; the distance outside for a simple case.
template <int N>
double hull_excess(const wedge::ConvexHull<N>& hull, const Vec<N>& x) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < hull.normals.size(); ++f) worst = std::max(worst, hull.normals[f].dot(x) - hull.offsets[f]);
  return worst;
}

// The origin inside the hull: its smallest facet offset (the penetration depth) and that facet's index.
template <int N>
double min_offset(const wedge::ConvexHull<N>& hull, std::size_t* facet = nullptr) {
  std::size_t best = 0;
  for (std::size_t f = 1; f < hull.offsets.size(); ++f)
    if (hull.offsets[f] < hull.offsets[best]) best = f;
  if (facet) *facet = best;
  return hull.offsets[best];
}

// Distance from the origin (outside) to the hull, by projection onto every face of every boundary cell.
template <int N>
double brute_distance(const wedge::ConvexHull<N>& hull) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& cell : hull.mesh.cells)
    for (int mask = 1; mask < (1 << N); ++mask) {
      Eigen::Matrix<double, N, Eigen::Dynamic> p(N, 0);
      for (int i = 0; i < N; ++i)
        if (mask & (1 << i)) {
          p.conservativeResize(Eigen::NoChange, p.cols() + 1);
          p.col(p.cols() - 1) = hull.mesh.vertices[cell[i]];
        }
      const int k = int(p.cols());
      Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(k + 1, k + 1);
      kkt.topLeftCorner(k, k) = p.transpose() * p;
      kkt.block(0, k, k, 1).setOnes();
      kkt.block(k, 0, 1, k).setOnes();
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k + 1);
      rhs[k] = 1.0;
      Eigen::VectorXd sol;
      if (!dense::solve_invertible(kkt, rhs, sol)) continue;
      if (sol.head(k).minCoeff() < -1e-12) continue;
      best = std::min(best, (p * sol.head(k)).norm());
    }
  return best;
}

// Exact separating-axis test for two boxes: A - B is a zonotope generated by the 2N box axes, so its
// facet normals are among the unit vectors orthogonal to N - 1 independent axes (a kernel by Eigen's
// FullPivLU). Returns the smallest support h_{A-B}(n) over those normals, both signs: positive iff the
// boxes overlap, and then it is the penetration depth (h(n) >= depth for every unit n, with equality at
// the nearest facet); negative: the boxes are at least that far apart. *normal gets the minimiser.
template <int N>
double box_sat(const BoxSupport<N>& a, const BoxSupport<N>& b, Vec<N>* normal = nullptr) {
  std::array<Vec<N>, 2 * N> axes;
  for (int i = 0; i < N; ++i) {
    axes[i] = a.rotation.col(i);
    axes[N + i] = b.rotation.col(i);
  }
  double best = std::numeric_limits<double>::infinity();
  for (unsigned mask = 0; mask < (1u << (2 * N)); ++mask) {
    if (__builtin_popcount(mask) != N - 1) continue;
    Eigen::Matrix<double, N - 1, N> m;
    for (int i = 0, row = 0; i < 2 * N; ++i)
      if (mask & (1u << i)) m.row(row++) = axes[i].transpose();
    Eigen::VectorXd kernel;
    if (!dense::kernel_vector(m, kernel)) continue;
    const Vec<N> n = kernel;
    for (const double sign : {1.0, -1.0}) {
      const Vec<N> d = sign * n;
      double h = d.dot(a.centre - b.centre);
      for (int i = 0; i < N; ++i) h += a.half[i] * std::abs(d.dot(a.rotation.col(i))) + b.half[i] * std::abs(d.dot(b.rotation.col(i)));
      if (h < best) {
        best = h;
        if (normal) *normal = d;
      }
    }
  }
  return best;
}

}  // namespace oracle
