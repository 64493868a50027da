// Display meshes (wedge/slicing/display_mesh.hpp): flat normals are the cells' outward unit normals
// (checked by an inside point and the mesh convention), smooth normals are the analytic surface
// normals of balls and round factors: x/|x| for the n-ball, x_A/|x_A| on the round side of a product.
// Tolerance 1e-12: one normalisation of O(1) coordinates.
#include <catch2/catch.hpp>
#include <cmath>

#include "test_util.hpp"
#include "wedge/error.hpp"
#include "wedge/slicing/display_mesh.hpp"

using namespace wedge;
using namespace wedge::slicing;

TEMPLATE_TEST_CASE("Display mesh: box cells carry their outward face normal at every corner", "[display_mesh]", D3, D4,
                   D5) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.3 + 0.1 * i;
  const DisplayMesh<N> m = display_mesh(Shape<N>::box(h), 2);
  REQUIRE(m.normals.size() == m.cells.size());
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    for (int j = 0; j < N; ++j) {
      const Vec<N>& n = m.normals[c][std::size_t(j)];
      Eigen::Index axis;
      n.cwiseAbs().maxCoeff(&axis);
      CHECK(std::abs(n[axis]) == Approx(1.0).epsilon(1e-12));
      // The face is x_axis = +-h_axis; the normal points away from the centre.
      CHECK(n[axis] * m.vertices[std::size_t(m.cells[c][std::size_t(j)])][axis] == Approx(h[axis]).epsilon(1e-12));
    }
}

TEMPLATE_TEST_CASE("Display mesh: n-ball normals are radial at every corner", "[display_mesh]", D3, D4, D5) {
  constexpr int N = TestType::value;
  const DisplayMesh<N> m = display_mesh(Shape<N>::ball(0.7), 3);
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    for (int j = 0; j < N; ++j) {
      const Vec<N> x = m.vertices[std::size_t(m.cells[c][std::size_t(j)])];
      CHECK((m.normals[c][std::size_t(j)] - x.normalized()).norm() < 1e-12);
    }
}

TEST_CASE("Display mesh: a 4D cubinder is round on its disk and flat on its caps", "[display_mesh]") {
  const double r = 0.5, hl = 0.3;
  const DisplayMesh<4> m = display_mesh(Shape<4>::cubinder(r, hl), 3);
  int round = 0, flat = 0;
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    std::array<Vec<4>, 4> p;
    for (int j = 0; j < 4; ++j) p[std::size_t(j)] = m.vertices[std::size_t(m.cells[c][std::size_t(j)])];
    const Vec<4> face = cell_normal<4>(p);
    // A cap cell lies in x_a = +-hl for an interval axis a in {2, 3}.
    bool cap = false;
    for (int a = 2; a < 4; ++a) {
      bool all = true;
      for (int j = 0; j < 4; ++j) all = all && std::abs(std::abs(p[std::size_t(j)][a]) - hl) < 1e-12;
      cap = cap || all;
    }
    for (int j = 0; j < 4; ++j) {
      const Vec<4>& n = m.normals[c][std::size_t(j)];
      if (cap) {
        CHECK((n - face).norm() < 1e-12);
      } else {
        const Vec<4> radial = Vec<4>(p[std::size_t(j)][0], p[std::size_t(j)][1], 0, 0).normalized();
        CHECK((n - radial).norm() < 1e-12);
      }
    }
    (cap ? flat : round) += 1;
  }
  CHECK(round > 0);
  CHECK(flat > 0);
}

TEST_CASE("Display mesh: cell_normal follows the mesh orientation convention", "[display_mesh]") {
  // det[n, p1 - p0, p2 - p0] > 0: for the counter-clockwise triangle in z = 0 seen from +z, n = +z.
  const std::array<Vec<3>, 3> tri{Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)};
  CHECK((cell_normal<3>(tri) - Vec<3>(0, 0, 1)).norm() < 1e-15);
  const std::array<Vec<3>, 3> flat{Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(2, 0, 0)};
  CHECK(cell_normal<3>(flat) == Vec<3>::Zero());
  CHECK_THROWS_AS(display_mesh(Shape<4>::halfspace(Vec<4>::Unit(1), 0.0)), wedge::Error);
}
