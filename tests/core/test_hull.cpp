// Convex hulls (wedge/hull.hpp) for n = 2..6: known hulls (box from its boundary grid with coplanar and
// interior points, cross-polytope, simplex) with their exact vertex/facet counts and volumes; random
// point sets (every point inside every facet half-space, every cell on a facet plane, closed outward
// mesh); degenerate input refused with a clear message and without Qhull writing to stderr.
// Tolerances: plane tests 1e-12 of the point-set scale (Qhull's normals are computed to round-off);
// volumes 1e-12 relative (a few hundred O(1) determinants).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "dense.hpp"
#include "wedge/error.hpp"
#include "wedge/hull.hpp"
#include "test_util.hpp"

namespace {

using wedge::ConvexHull;
using wedge::Mat;
using wedge::SimplexMesh;
using wedge::Vec;


double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Redirects file descriptor 2 into a temporary file for the lifetime of the object.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    tmp_ = std::tmpfile();
    saved_ = dup(2);
    dup2(fileno(tmp_), 2);
  }
  ~StderrCapture() {
    if (tmp_) text();
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  std::string text() {
    if (!tmp_) return text_;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    std::rewind(tmp_);
    char buf[256];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, tmp_)) > 0) text_.append(buf, n);
    std::fclose(tmp_);
    tmp_ = nullptr;
    return text_;
  }

 private:
  std::FILE* tmp_ = nullptr;
  int saved_ = -1;
  std::string text_;
};

template <int N>
void check_hull_contract(const ConvexHull<N>& hull, const std::vector<Vec<N>>& pts) {
  double scale = 0.0;
  for (const Vec<N>& p : pts) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double eps = 1e-12 * scale;
  REQUIRE(hull.normals.size() == hull.offsets.size());
  REQUIRE(hull.vertex_of_point.size() == pts.size());
  CHECK_NOTHROW(wedge::validate(hull.mesh));
  for (const Vec<N>& n : hull.normals) CHECK(std::abs(n.norm() - 1.0) <= 1e-14);
  // Every input point is inside every facet half-space; the non-vertices are the points not extreme.
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double worst = -INFINITY;
    for (std::size_t f = 0; f < hull.normals.size(); ++f)
      worst = std::max(worst, hull.normals[f].dot(pts[i]) - hull.offsets[f]);
    REQUIRE(worst <= eps);
    if (worst < -eps) REQUIRE(hull.vertex_of_point[i] == -1);  // strictly interior
    if (hull.vertex_of_point[i] >= 0) REQUIRE(hull.mesh.vertices[std::size_t(hull.vertex_of_point[i])] == pts[i]);
  }
  // Every cell lies in a facet plane, on the outer side of the interior (validate checks closed/outward).
  for (const auto& c : hull.mesh.cells) {
    bool on_facet = false;
    for (std::size_t f = 0; f < hull.normals.size() && !on_facet; ++f) {
      bool all = true;
      for (int j = 0; j < N; ++j)
        all = all && std::abs(hull.normals[f].dot(hull.mesh.vertices[std::size_t(c[j])]) - hull.offsets[f]) <= eps;
      on_facet = all;
    }
    REQUIRE(on_facet);
  }
}

}  // namespace

TEMPLATE_TEST_CASE("Hull of a box's boundary grid plus interior points is the box", "[hull]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.5 + 0.2 * i;
  std::vector<Vec<N>> pts = wedge::box_mesh<N>(h, 2).vertices;  // corners, edge midpoints, face centres..
  pts.push_back(Vec<N>::Zero());
  pts.push_back(0.3 * h);
  const ConvexHull<N> hull = wedge::convex_hull<N>(pts);
  check_hull_contract<N>(hull, pts);
  double volume = 1.0;
  for (int i = 0; i < N; ++i) volume *= 2.0 * h[i];
  CHECK(std::abs(wedge::signed_volume(hull.mesh) - volume) <= 1e-12 * volume);
  // 2N facets, normals +-e_i, offsets h_i.
  REQUIRE(hull.normals.size() == std::size_t(2 * N));
  for (std::size_t f = 0; f < hull.normals.size(); ++f) {
    int axis = -1;
    hull.normals[f].cwiseAbs().maxCoeff(&axis);
    CHECK(std::abs(std::abs(hull.normals[f][axis]) - 1.0) <= 1e-14);
    CHECK(hull.offsets[f] == Approx(h[axis]).epsilon(1e-14));
  }
  // All 2^N corners are vertices; the interior points are not.
  for (std::size_t i = 0; i < pts.size(); ++i) {
    bool corner = true;
    for (int a = 0; a < N; ++a) corner = corner && std::abs(pts[i][a]) == h[a];
    if (corner) CHECK(hull.vertex_of_point[i] >= 0);
  }
  CHECK(hull.vertex_of_point[pts.size() - 1] == -1);
  CHECK(hull.vertex_of_point[pts.size() - 2] == -1);
  // Qhull merges each coplanar facet; the cells triangulating it all have positive volume (validate).
  CHECK(hull.mesh.cells.size() >= std::size_t(2 * N) * std::size_t(factorial(N - 1)));
}

TEMPLATE_TEST_CASE("Hull of the cross-polytope and of a simplex", "[hull]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::vector<Vec<N>> cross;
  for (int i = 0; i < N; ++i) {
    cross.push_back(Vec<N>::Unit(i) * 1.5);
    cross.push_back(-Vec<N>::Unit(i) * 1.5);
  }
  const ConvexHull<N> c = wedge::convex_hull<N>(cross);
  check_hull_contract<N>(c, cross);
  CHECK(c.normals.size() == std::size_t(1 << N));  // one simplicial facet per orthant
  CHECK(c.mesh.cells.size() == std::size_t(1 << N));
  CHECK(wedge::signed_volume(c.mesh) == Approx(std::pow(2.0 * 1.5, N) / factorial(N)).epsilon(1e-12));
  for (const Vec<N>& n : c.normals) CHECK(n.cwiseAbs().isApprox(Vec<N>::Constant(1.0 / std::sqrt(double(N))), 1e-14));

  std::mt19937_64 rng(11 + N);
  std::normal_distribution<double> g;
  std::vector<Vec<N>> simplex(N + 1);
  for (Vec<N>& v : simplex)
    for (int i = 0; i < N; ++i) v[i] = g(rng);
  Mat<N> e;
  for (int j = 0; j < N; ++j) e.col(j) = simplex[std::size_t(j + 1)] - simplex[0];
  const ConvexHull<N> s = wedge::convex_hull<N>(simplex);
  check_hull_contract<N>(s, simplex);
  CHECK(s.mesh.cells.size() == std::size_t(N + 1));
  CHECK(s.mesh.vertices.size() == std::size_t(N + 1));
  CHECK(wedge::signed_volume(s.mesh) == Approx(std::abs(det(e)) / factorial(N)).epsilon(1e-12));
  CHECK(wedge::convex_hull_mesh<N>(simplex).cells == s.mesh.cells);
}

TEMPLATE_TEST_CASE("Hull of random points: contains every point, cells on facets, closed and outward", "[hull]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(1234 + N);
  std::normal_distribution<double> g;
  for (int count : {N + 2, 6 * N}) {
    std::vector<Vec<N>> pts(static_cast<std::size_t>(count));
    for (Vec<N>& v : pts)
      for (int i = 0; i < N; ++i) v[i] = 2.0 + g(rng) * (1.0 + 0.3 * i);  // off the origin, anisotropic
    const ConvexHull<N> hull = wedge::convex_hull<N>(pts);
    check_hull_contract<N>(hull, pts);
    // The hull contains the simplex of any N+1 input points.
    Mat<N> e;
    for (int j = 0; j < N; ++j) e.col(j) = pts[std::size_t(j + 1)] - pts[0];
    CHECK(wedge::signed_volume(hull.mesh) >= std::abs(det(e)) / factorial(N));
  }
}

TEST_CASE("Hull of cospherical points (Qhull merges, we triangulate coplanar facets)", "[hull]") {
  // The vertices of a tesseract's boundary grid rounded onto the 3-sphere, and 3D/5D n-ball meshes.
  const auto b4 = wedge::ball_mesh<4>(1.0, 3);
  const ConvexHull<4> h4 = wedge::convex_hull<4>(b4.vertices);
  check_hull_contract<4>(h4, b4.vertices);
  CHECK(wedge::signed_volume(h4.mesh) >= wedge::signed_volume(b4) * (1 - 1e-12));  // the hull contains the mesh
  const auto b3 = wedge::ball_mesh<3>(2.0, 6);
  check_hull_contract<3>(wedge::convex_hull<3>(b3.vertices), b3.vertices);
  const auto b5 = wedge::ball_mesh<5>(1.0, 2);
  check_hull_contract<5>(wedge::convex_hull<5>(b5.vertices), b5.vertices);
}

TEST_CASE("Degenerate hull input is refused with a clear message", "[hull]") {
  REQUIRE_THROWS_WITH(wedge::convex_hull<3>({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)}),
                      Catch::Contains("needs at least 4 points (got 3)"));
  REQUIRE_THROWS_WITH(wedge::convex_hull<4>({}), Catch::Contains("needs at least 5 points"));
  REQUIRE_THROWS_WITH(wedge::convex_hull<3>(std::vector<Vec<3>>(6, Vec<3>(1, 2, 3))), Catch::Contains("all 6 points coincide"));
  // Collinear and coplanar in 3D, a hyperplane in 4D, a 2-plane in 5D.
  std::vector<Vec<3>> line, plane;
  for (int i = 0; i < 6; ++i) {
    line.push_back(Vec<3>(1, 2, 3) + i * Vec<3>(0.5, -1, 2));
    plane.push_back(Vec<3>(i, i * i, 0.25 * i + 0.5 * i * i));  // z = 0.25 x + 0.5 y
  }
  REQUIRE_THROWS_WITH(wedge::convex_hull<3>(line), Catch::Contains("flat: they span only a 1-dimensional"));
  REQUIRE_THROWS_WITH(wedge::convex_hull<3>(plane), Catch::Contains("flat: they span only a 2-dimensional affine subspace of R^3"));
  std::mt19937_64 rng(8);
  std::normal_distribution<double> g;
  std::vector<Vec<4>> hyper;
  for (int i = 0; i < 20; ++i) {
    Vec<4> v(g(rng), g(rng), g(rng), 0.0);
    v[3] = 1.0 + v[0] - 2.0 * v[2];
    hyper.push_back(v);
  }
  REQUIRE_THROWS_WITH(wedge::convex_hull<4>(hyper), Catch::Contains("span only a 3-dimensional affine subspace of R^4"));
  std::vector<Vec<5>> flat5;
  for (int i = 0; i < 20; ++i) {
    const double a = g(rng), b = g(rng);
    Vec<5> v;
    v << a, b, a + b, a - b, 2 * a;
    flat5.push_back(v);
  }
  REQUIRE_THROWS_WITH(wedge::convex_hull<5>(flat5), Catch::Contains("span only a 2-dimensional"));
  std::vector<Vec<3>> bad = {Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0, 0, NAN)};
  REQUIRE_THROWS_WITH(wedge::convex_hull<3>(bad), Catch::Contains("point 3 has a non-finite coordinate"));
  bad[3] = Vec<3>(0, INFINITY, 1);
  REQUIRE_THROWS_AS(wedge::convex_hull<3>(bad), wedge::Error);
}

TEST_CASE("Nearly flat input gives a valid hull or wedge::Error, and Qhull never writes to stderr", "[hull]") {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> g;
  StderrCapture capture;
  for (double thickness : {1e-6, 1e-9, 1e-10, 1e-13, 0.0}) {
    std::vector<Vec<4>> pts;
    for (int i = 0; i < 30; ++i) pts.push_back(Vec<4>(g(rng), g(rng), g(rng), thickness * g(rng)));
    try {
      const ConvexHull<4> h = wedge::convex_hull<4>(pts);
      CHECK_NOTHROW(wedge::validate(h.mesh));
    } catch (const wedge::Error& e) {
      CHECK(std::string(e.what()).find("convex hull") != std::string::npos);
    }
  }
  // Thousands of points on a box surface (many coplanar, merged by Qhull).
  const auto grid = wedge::box_mesh<3>(Vec<3>(1, 2, 3), 12).vertices;
  CHECK(wedge::convex_hull<3>(grid).normals.size() == 6);
  CHECK(capture.text().empty());
}

// Coordinates beyond what Qhull's determinants can hold are refused before Qhull sees them (found by
// fuzzing: a 24-cell of circumradius 2.2e235 m crashed inside Qhull); small and ordinary scales still work.
TEST_CASE("Hull input with coordinates too large for Qhull is refused, not crashed on", "[hull]") {
  std::vector<Vec<4>> simplex = {Vec<4>::Zero(), Vec<4>::UnitX(), Vec<4>::UnitY(), Vec<4>(0, 0, 1, 0), Vec<4>(0, 0, 0, 1)};
  for (Vec<4>& p : simplex) p *= 2.2e235;
  REQUIRE_THROWS_WITH(wedge::convex_hull<4>(simplex), Catch::Contains("at most 1e+30 m is supported"));
  for (const double scale : {1e29, 1e-6}) {
    INFO(scale);
    std::vector<Vec<4>> s = {Vec<4>::Zero(), Vec<4>::UnitX(), Vec<4>::UnitY(), Vec<4>(0, 0, 1, 0), Vec<4>(0, 0, 0, 1)};
    for (Vec<4>& p : s) p *= scale;
    const ConvexHull<4> hull = wedge::convex_hull<4>(s);
    CHECK(hull.mesh.vertices.size() == 5);
  }
}
