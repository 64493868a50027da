// Simplicial boundary meshes (wedge/mesh.hpp): the box and round-product generators for n = 2..6 (cell
// and vertex counts from the grid formulas, vertices on the true surface, closed, outward, exact box
// volume), and validate()'s refusal of each kind of broken mesh with a message naming the problem.
// Tolerances: box coordinates are exact (grid values h (2g - s)/s are symmetric and the surface test
// compares with h itself); volumes 1e-12 relative (sums of a few thousand O(1) determinants); points
// of round meshes lie on spheres to 1e-14 relative (one scaling by |x|_inf/|x|_2).
#include <catch2/catch.hpp>
#include <cmath>
#include <type_traits>
#include <vector>

#include "dense.hpp"
#include "wedge/error.hpp"
#include "wedge/mesh.hpp"
#include "test_util.hpp"

namespace {

using wedge::Mat;
using wedge::ProductFactor;
using wedge::SimplexMesh;
using wedge::Vec;


long long ipow(long long b, int e) {
  long long r = 1;
  for (int i = 0; i < e; ++i) r *= b;
  return r;
}
long long factorial(int n) { return n <= 1 ? 1 : n * factorial(n - 1); }

template <int N>
double det_from_origin(const SimplexMesh<N>& m, const std::array<int, N>& c) {
  Mat<N> a;
  for (int j = 0; j < N; ++j) a.col(j) = m.vertices[std::size_t(c[j])];
  return det(a);
}

// The surface of a tetrahedron, oriented outward here (the fixture does not use the library).
SimplexMesh<3> tetrahedron() {
  SimplexMesh<3> m;
  m.vertices = {Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0, 0, 1)};
  const Vec<3> c(0.25, 0.25, 0.25);
  for (std::array<int, 3> f : {std::array<int, 3>{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}) {
    Mat<3> a;
    for (int j = 0; j < 3; ++j) a.col(j) = m.vertices[std::size_t(f[std::size_t(j)])] - c;
    if (det(a) < 0) std::swap(f[0], f[1]);
    m.cells.push_back(f);
  }
  return m;
}

SimplexMesh<2> square() {
  SimplexMesh<2> m;
  m.vertices = {Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)};
  m.cells = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};  // counter-clockwise
  return m;
}

}  // namespace

TEMPLATE_TEST_CASE("box_mesh: grid counts, vertices on the box, closed and outward, exact volume", "[mesh]", D2, D3, D4,
                   D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.6 + 0.35 * i;
  double volume = 1.0;
  for (int i = 0; i < N; ++i) volume *= 2.0 * h[i];
  for (int s : (N == 6 ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 3})) {
    INFO("subdivisions " << s);
    const SimplexMesh<N> m = wedge::box_mesh<N>(h, s);
    // 2N facets of s^(N-1) grid cubes, (N-1)! Kuhn simplices each; the boundary grid points.
    CHECK((long long)m.cells.size() == 2 * N * ipow(s, N - 1) * factorial(N - 1));
    CHECK((long long)m.cells.size() == wedge::box_mesh_cell_count(N, s));
    CHECK((long long)m.vertices.size() == ipow(s + 1, N) - ipow(s - 1, N));
    for (const Vec<N>& v : m.vertices) {
      double on = 0.0;
      for (int i = 0; i < N; ++i) {
        REQUIRE(std::abs(v[i]) <= h[i]);
        on = std::max(on, std::abs(v[i]) / h[i]);
      }
      REQUIRE(on == 1.0);
    }
    // Every cell lies in one facet and is positively oriented seen from the centre (outward).
    for (const auto& c : m.cells) {
      bool in_facet = false;
      for (int a = 0; a < N && !in_facet; ++a) {
        bool all = true;
        for (int j = 0; j < N; ++j) all = all && m.vertices[std::size_t(c[j])][a] == m.vertices[std::size_t(c[0])][a];
        in_facet = all && std::abs(m.vertices[std::size_t(c[0])][a]) == h[a];
      }
      REQUIRE(in_facet);
      REQUIRE(det_from_origin<N>(m, c) > 0.0);
    }
    CHECK_NOTHROW(wedge::validate(m));
    CHECK(std::abs(wedge::signed_volume(m) - volume) <= 1e-12 * volume);
  }
}

TEMPLATE_TEST_CASE("round_product_mesh: n-balls and products are valid with every vertex on the surface", "[mesh]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double r = 1.7;
  for (int s : (N >= 5 ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 3, 5})) {
    INFO("subdivisions " << s);
    const SimplexMesh<N> ball = wedge::ball_mesh<N>(r, s);
    CHECK((long long)ball.cells.size() == wedge::box_mesh_cell_count(N, s));
    for (const Vec<N>& v : ball.vertices) REQUIRE(std::abs(v.norm() - r) <= 1e-14 * r);
    for (const auto& c : ball.cells) REQUIRE(det_from_origin<N>(ball, c) > 0.0);  // star-shaped
    CHECK_NOTHROW(wedge::validate(ball));
    const double v = wedge::signed_volume(ball);
    CHECK(v > 0.0);
  }
  if constexpr (N >= 3) {
    // A disk on axes {0, 2}, the rest intervals of different half-lengths.
    std::vector<ProductFactor> f{ProductFactor::ball({2, 0}, 0.8)};
    for (int a = 1; a < N; ++a)
      if (a != 2) f.push_back(ProductFactor::interval(a, 0.3 + 0.1 * a));
    const SimplexMesh<N> m = wedge::round_product_mesh<N>(f, N <= 4 ? 4 : 2);
    CHECK_NOTHROW(wedge::validate(m));
    for (const Vec<N>& x : m.vertices) {
      const double disk = std::hypot(x[0], x[2]) / 0.8;
      double on = disk;
      REQUIRE(disk <= 1.0 + 1e-14);
      for (int a = 1; a < N; ++a)
        if (a != 2) {
          REQUIRE(std::abs(x[a]) <= 0.3 + 0.1 * a);
          on = std::max(on, std::abs(x[a]) / (0.3 + 0.1 * a));
        }
      REQUIRE(std::abs(on - 1.0) <= 1e-14);
    }
  }
  if constexpr (N >= 4) {
    const SimplexMesh<N> m = wedge::round_product_mesh<N>(
        [] {
          std::vector<ProductFactor> f{ProductFactor::ball({0, 1}, 1.0), ProductFactor::ball({2, 3}, 0.5)};
          for (int a = 4; a < N; ++a) f.push_back(ProductFactor::interval(a, 0.5));
          return f;
        }(),
        2);
    CHECK_NOTHROW(wedge::validate(m));
  }
}

TEST_CASE("Tessellation level: default levels and the cell limit", "[mesh]") {
  CHECK(wedge::default_subdivisions(3) == 8);
  CHECK(wedge::box_mesh_cell_count(3, wedge::default_subdivisions(3)) == 6 * 64 * 2);
  for (int n = 2; n <= 6; ++n) CHECK(wedge::box_mesh_cell_count(n, wedge::default_subdivisions(n)) <= 50000);
  REQUIRE_THROWS_WITH(wedge::box_mesh<3>(Vec<3>::Ones(), 0), Catch::Contains("subdivisions must be at least 1"));
  REQUIRE_THROWS_WITH(wedge::box_mesh<6>(Vec<6>::Ones(), 40), Catch::Contains("cells in 6D"));
  REQUIRE_THROWS_WITH(wedge::box_mesh<3>(Vec<3>(1, -1, 1), 1), Catch::Contains("half-extent 1 must be positive"));
  REQUIRE_THROWS_WITH(wedge::box_mesh<3>(Vec<3>(1, NAN, 1), 1), Catch::Contains("half-extent 1 must be positive"));
}

TEST_CASE("Round product factors must partition the axes with positive sizes", "[mesh]") {
  using F = ProductFactor;
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({}, 1), Catch::Contains("no factors"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({0, 1}, 1.0), F::interval(1, 1.0)}, 1),
                      Catch::Contains("axis 1 appears in factors 0 and 1"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({0, 1}, 1.0)}, 1), Catch::Contains("axis 2 is not covered"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({0, 1}, 1.0), F::interval(3, 1.0)}, 1),
                      Catch::Contains("axis 3, out of range"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({0, 1}, 0.0), F::interval(2, 1.0)}, 1),
                      Catch::Contains("non-positive or non-finite radius"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({0, 1}, 1.0), F::interval(2, -1.0)}, 1),
                      Catch::Contains("non-positive or non-finite half-length"));
  REQUIRE_THROWS_WITH(
      wedge::round_product_mesh<3>({F::ball({0}, 1.0), F{{1, 2}, F::Kind::Interval, 1.0}}, 1),
      Catch::Contains("is an interval but has 2 axes"));
  REQUIRE_THROWS_WITH(wedge::round_product_mesh<3>({F::ball({}, 1.0), F::ball({0, 1, 2}, 1.0)}, 1),
                      Catch::Contains("has no axes"));
}

TEST_CASE("validate: valid fixtures pass", "[mesh]") {
  CHECK_NOTHROW(wedge::validate(square()));
  CHECK_NOTHROW(wedge::validate(tetrahedron()));
  CHECK(wedge::signed_volume(square()) == Approx(1.0));
  CHECK(wedge::signed_volume(tetrahedron()) == Approx(1.0 / 6.0));
}

TEST_CASE("validate: every kind of broken mesh is refused with a message naming it", "[mesh]") {
  SECTION("no cells") {
    SimplexMesh<3> m = tetrahedron();
    m.cells.clear();
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("no cells"));
  }
  SECTION("index out of range") {
    SimplexMesh<3> m = tetrahedron();
    m.cells[2][1] = 7;
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("cell 2 refers to vertex 7, out of range"));
    m.cells[2][1] = -1;
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("out of range"));
  }
  SECTION("repeated vertex in a cell") {
    SimplexMesh<3> m = tetrahedron();
    m.cells[1][2] = m.cells[1][0];
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("cell 1 repeats vertex"));
  }
  SECTION("non-finite coordinates") {
    SimplexMesh<3> m = tetrahedron();
    m.vertices[3][1] = NAN;
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("vertex 3 has a non-finite coordinate"));
    m.vertices[3][1] = INFINITY;
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("non-finite"));
  }
  SECTION("zero-volume cells") {
    SimplexMesh<3> m = tetrahedron();
    m.vertices[3] = m.vertices[0];  // two indices, one position: the cells using both are flat
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("is degenerate (zero 2-volume"));
    SimplexMesh<3> c = tetrahedron();
    c.vertices[3] = Vec<3>(0.5, 0.5, 0.0);  // on the line through vertices 1 and 2
    REQUIRE_THROWS_WITH(wedge::validate(c), Catch::Contains("degenerate"));
    SimplexMesh<2> s = square();
    s.vertices[2] = s.vertices[1];
    REQUIRE_THROWS_WITH(wedge::validate(s), Catch::Contains("degenerate (zero 1-volume: its vertices coincide)"));
  }
  SECTION("open mesh") {
    SimplexMesh<3> m = tetrahedron();
    m.cells.pop_back();
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("open mesh"));
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("is not shared with any other cell"));
    SimplexMesh<4> b = wedge::box_mesh<4>(Vec<4>::Ones(), 2);
    b.cells.erase(b.cells.begin() + 17);
    REQUIRE_THROWS_WITH(wedge::validate(b), Catch::Contains("open mesh: 2-face"));
  }
  SECTION("one flipped cell") {
    SimplexMesh<3> m = tetrahedron();
    std::swap(m.cells[2][0], m.cells[2][1]);
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("inconsistently oriented mesh"));
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("flipped cell"));
    SimplexMesh<5> b = wedge::box_mesh<5>(Vec<5>::Ones(), 1);
    std::swap(b.cells[40][3], b.cells[40][4]);
    REQUIRE_THROWS_WITH(wedge::validate(b), Catch::Contains("inconsistently oriented mesh"));
  }
  SECTION("non-manifold: two tetrahedra sharing only an edge") {
    SimplexMesh<3> m = tetrahedron();
    // A second tetrahedron on the other side of the x axis, sharing only the edge {0, 1}.
    const int base = int(m.vertices.size());
    m.vertices.push_back(Vec<3>(0, -1, 0));  // 4
    m.vertices.push_back(Vec<3>(0, 0, -1));  // 5
    // The tetrahedron (0, 1, 4, 5), oriented outward by the same rule as the fixture.
    const Vec<3> c = (m.vertices[0] + m.vertices[1] + m.vertices[4] + m.vertices[5]) / 4.0;
    for (std::array<int, 3> f : {std::array<int, 3>{1, base, base + 1}, {0, base, base + 1}, {0, 1, base + 1}, {0, 1, base}}) {
      Mat<3> a;
      for (int j = 0; j < 3; ++j) a.col(j) = m.vertices[std::size_t(f[std::size_t(j)])] - c;
      if (det(a) < 0) std::swap(f[0], f[1]);
      m.cells.push_back(f);
    }
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("non-manifold mesh: 1-face {0, 1} is shared by 4 cells"));
  }
  SECTION("inside-out") {
    SimplexMesh<3> m = tetrahedron();
    for (auto& c : m.cells) std::swap(c[0], c[1]);
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("inside-out mesh"));
    SimplexMesh<2> s = square();
    for (auto& c : s.cells) std::swap(c[0], c[1]);  // clockwise
    REQUIRE_THROWS_WITH(wedge::validate(s), Catch::Contains("inside-out mesh"));
    SimplexMesh<6> b = wedge::box_mesh<6>(Vec<6>::Ones(), 1);
    for (auto& c : b.cells) std::swap(c[2], c[5]);
    REQUIRE_THROWS_WITH(wedge::validate(b), Catch::Contains("inside-out"));
  }
  SECTION("degenerate body: a doubly covered triangle") {
    SimplexMesh<3> m;
    m.vertices = {Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)};
    m.cells = {{0, 1, 2}, {0, 2, 1}};
    REQUIRE_THROWS_WITH(wedge::validate(m), Catch::Contains("degenerate body"));
  }
}
