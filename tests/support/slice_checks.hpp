// Independent checks of 3D slice meshes (plain loops, nothing from the slicer): closedness and
// orientation through directed edges, enclosed volume and area, and the exact cross-section of a placed
// box as the hull of the vertices of its constraint system (brute force over plane triples + Qhull).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dense.hpp"
#include "wedge/hull.hpp"
#include "wedge/mesh.hpp"
#include "wedge/slicing/display_mesh.hpp"

namespace slice_checks {

using wedge::Vec;

// "" if every directed edge (a, b) of a triangle appears once and its reverse (b, a) once (closed,
// 2-manifold, consistently oriented), else the first problem.
inline std::string closed_and_oriented(const wedge::slicing::DisplayMesh<3>& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.cells)
    for (int j = 0; j < 3; ++j) {
      const int a = t[std::size_t(j)], b = t[std::size_t((j + 1) % 3)];
      if (a == b) return "triangle with a repeated vertex";
      if (a < 0 || std::size_t(a) >= m.vertices.size()) return "vertex index out of range";
      ++directed[{a, b}];
    }
  for (const auto& [e, count] : directed) {
    if (count != 1) return "directed edge used " + std::to_string(count) + " times";
    const auto it = directed.find({e.second, e.first});
    if (it == directed.end()) return "open edge " + std::to_string(e.first) + "-" + std::to_string(e.second);
  }
  return "";
}

inline double volume(const wedge::slicing::DisplayMesh<3>& m) {
  double v = 0.0;
  for (const auto& t : m.cells) {
    Eigen::Matrix3d a;
    for (int j = 0; j < 3; ++j) a.col(j) = m.vertices[std::size_t(t[std::size_t(j)])];
    v += a.determinant() / 6.0;
  }
  return v;
}

inline double area(const wedge::slicing::DisplayMesh<3>& m) {
  double s = 0.0;
  for (const auto& t : m.cells) {
    const Vec<3> a = m.vertices[std::size_t(t[0])], b = m.vertices[std::size_t(t[1])], c = m.vertices[std::size_t(t[2])];
    s += 0.5 * (b - a).cross(c - a).norm();
  }
  return s;
}

// A lower bound on how far a closed mesh around the origin keeps from it: the least distance from the
// origin to the affine hull of any cell. The solid then contains the ball of that radius (its boundary
// stays outside the ball, and the ball is connected and holds the origin, which is inside).
template <int N>
double inner_radius(const wedge::SimplexMesh<N>& m) {
  double best = INFINITY;
  for (const auto& c : m.cells) {
    const Vec<N> v0 = m.vertices[std::size_t(c[0])];
    Eigen::Matrix<double, N, N - 1> e;
    for (int j = 1; j < N; ++j) e.col(j - 1) = m.vertices[std::size_t(c[std::size_t(j)])] - v0;
    const Eigen::VectorXd coef = dense::least_squares(e, -v0);
    best = std::min(best, (v0 + e * coef).norm());
  }
  return best;
}

// The volume of {y in R^3 : |M^T (origin + F y - p)|_i <= h_i for all i}: the slice of the box [-h, h]
// placed by x_world = M x + p, by the 3-flat origin + F y. Every vertex of that polytope solves three of
// the 2N constraints with equality; the feasible solutions' convex hull (Qhull) has the volume.
template <int N>
double box_section_volume(const Vec<N>& h, const Eigen::Matrix<double, N, N>& rot, const Vec<N>& p,
                          const Vec<N>& origin, const Eigen::Matrix<double, N, 3>& frame) {
  const Eigen::Matrix<double, N, 3> a = rot.transpose() * frame;   // rows: constraint normals
  const Vec<N> c = rot.transpose() * (origin - p);
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> rhs;
  for (int i = 0; i < N; ++i) {
    rows.push_back(a.row(i).transpose());
    rhs.push_back(h[i] - c[i]);  // a_i y <= h_i - c_i
    rows.push_back(-a.row(i).transpose());
    rhs.push_back(h[i] + c[i]);  // -a_i y <= h_i + c_i
  }
  std::vector<Vec<3>> pts;
  const std::size_t k = rows.size();
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i + 1; j < k; ++j)
      for (std::size_t l = j + 1; l < k; ++l) {
        Eigen::Matrix3d m;
        m << rows[i].transpose(), rows[j].transpose(), rows[l].transpose();
        if (std::abs(m.determinant()) < 1e-9) continue;
        const Eigen::Vector3d y = m.fullPivLu().solve(Eigen::Vector3d(rhs[i], rhs[j], rhs[l]));
        bool ok = true;
        for (std::size_t q = 0; q < k && ok; ++q) ok = rows[q].dot(y) <= rhs[q] + 1e-9;
        if (ok) pts.push_back(y);
      }
  if (pts.size() < 4) return 0.0;
  try {
    return wedge::signed_volume<3>(wedge::convex_hull_mesh<3>(pts));
  } catch (const std::exception&) {
    return 0.0;  // flat: the flat touches the box in a face or less
  }
}

}  // namespace slice_checks
