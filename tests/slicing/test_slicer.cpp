// The slicer (wedge/slicing/slicer.hpp) against geometry it does not compute itself:
//  * a tesseract of side s cut at w = 0 is the cube: volume s^3, area 6 s^2, closed and outward;
//  * rotated and shifted boxes in 4D, 5D and 6D (cut down to 3D) against the exact cross-section volume
//    from an independent constraint-vertex enumeration and Qhull (support/slice_checks.hpp);
//  * n-balls: the cut is a sphere of radius sqrt(r^2 - w^2). The mesh's vertices are on the true
//    sphere, so the body lies inside the ball of radius r, and it contains the ball of radius r_in, the
//    least distance from the centre to a cell's affine hull (slice_checks::inner_radius). The slice lies
//    between the spheres of radius rho_in = sqrt(r_in^2 - w^2) and rho: vertices and volume must fall
//    in that shell and the area in [4 pi rho_in^2, 4 pi rho^2] (a closed surface enclosing a ball is at
//    least as large as its sphere; a convex one inside a ball at most as large). Linear interpolation
//    of the exact radial normals x/r along an edge gives the radial normal of the cut point itself, so
//    the slice's normals must be radial to round-off;
//  * thousands of random orientations and offsets: every slice closed, consistently oriented, outward.
// Tolerances: volumes of exact (box) sections 1e-9 relative (sums of O(100) determinants of O(1) points,
// and the oracle's vertices are solved to ~1e-13); closedness is exact (combinatorial).
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "slice_checks.hpp"
#include "test_util.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/hull.hpp"
#include "wedge/shape.hpp"
#include "wedge/slicing/slicer.hpp"

namespace {

using namespace wedge;
using namespace wedge::slicing;
using slice_checks::area;
using slice_checks::closed_and_oriented;
using slice_checks::volume;

template <int N>
Mat<N> random_rotation(std::mt19937_64& rng) {
  return to_matrix(wedge::exp(random_bivector<N>(rng, 2.0)));
}

template <int N>
Vec<N> random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> nd;
  Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = nd(rng);
  return v.normalized();
}

// A plane with a random normal, drawn first, at the offset offset() draws: two draws in a fixed order
// (the arguments of one call are evaluated in an order each compiler picks).
template <int N, class Draw>
Hyperplane<N> random_plane(std::mt19937_64& rng, Draw&& offset) {
  const Vec<N> normal = random_unit<N>(rng);
  return Hyperplane<N>::through(normal, offset());
}

template <int N>
SliceChain<N> random_chain(std::mt19937_64& rng, double spread) {
  SliceChain<N> c;
  if constexpr (N > 3) {
    std::uniform_real_distribution<double> u(-spread, spread);
    c.plane = random_plane<N>(rng, [&] { return u(rng); });
    c.rest = random_chain<N - 1>(rng, spread);
  }
  return c;
}

}  // namespace

TEST_CASE("Slicer: a tesseract of side s cut at w = 0 is a closed cube of volume s^3 and area 6 s^2", "[slicer]") {
  const double s = 1.3;
  for (int sub : {1, 3}) {
    const DisplayMesh<4> mesh = display_mesh(Shape<4>::box(Vec<4>::Constant(s / 2)), sub);
    MeshSlicer<4> slicer(mesh);
    const DisplayMesh<3> cube = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(0.0));
    INFO("subdivisions " << sub);
    REQUIRE(closed_and_oriented(cube) == "");
    CHECK(volume(cube) == Approx(s * s * s).epsilon(1e-12));
    CHECK(area(cube) == Approx(6 * s * s).epsilon(1e-12));
    for (const Vec<3>& v : cube.vertices) CHECK(v.cwiseAbs().maxCoeff() == Approx(s / 2).epsilon(1e-15));
    // Flat faces: every corner normal is the axis of the face it lies on.
    for (std::size_t c = 0; c < cube.cells.size(); ++c)
      for (const Vec<3>& n : cube.normals[c]) {
        Eigen::Index axis;
        n.cwiseAbs().maxCoeff(&axis);
        CHECK(std::abs(n[axis]) == Approx(1.0).epsilon(1e-12));
        CHECK(cube.vertices[std::size_t(cube.cells[c][0])][axis] * n[axis] == Approx(s / 2).epsilon(1e-12));
      }
  }
}

TEST_CASE("Slicer: vertices exactly on the plane count as above, so a cut through a facet stays closed", "[slicer]") {
  const double s = 1.0;
  const DisplayMesh<4> mesh = display_mesh(Shape<4>::box(Vec<4>::Constant(s / 2)), 2);
  MeshSlicer<4> slicer(mesh);
  // w = +s/2: the top facet is on the plane (above), everything else below: the cube itself.
  const DisplayMesh<3> top = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(s / 2));
  REQUIRE(closed_and_oriented(top) == "");
  CHECK(volume(top) == Approx(s * s * s).epsilon(1e-12));
  // w = -s/2: every vertex is on or above the plane: no cell is cut.
  CHECK(slicer.slice(Placement<4>{}, Hyperplane<4>::axis(-s / 2)).empty());
  // Through the grid's middle vertices (w = 0 is a grid plane at subdivision 2).
  const DisplayMesh<3> mid = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(0.0));
  REQUIRE(closed_and_oriented(mid) == "");
  CHECK(volume(mid) == Approx(s * s * s).epsilon(1e-12));
}

TEST_CASE("Slicer: rotated, shifted boxes in 4D match the exact cross-section volume", "[slicer]") {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec<4> h(0.5, 0.3, 0.7, 0.4);
  const DisplayMesh<4> mesh = display_mesh(Shape<4>::box(h), 1);
  MeshSlicer<4> slicer(mesh);
  int nonempty = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Placement<4> pl{random_rotation<4>(rng), Vec<4>{u(rng), u(rng), u(rng), 0.4 * u(rng)}};
    const Hyperplane<4> plane = trial % 2 ? Hyperplane<4>::axis(0.3 * u(rng))
                                          : random_plane<4>(rng, [&] { return 0.3 * u(rng); });
    const DisplayMesh<3> cut = slicer.slice(pl, plane);
    SliceChain<4> chain;
    chain.plane = plane;
    const Flat3<4> flat = chain.flat();
    const double exact = slice_checks::box_section_volume<4>(h, pl.rotation, pl.translation, flat.origin, flat.frame);
    INFO("trial " << trial);
    REQUIRE(closed_and_oriented(cut) == "");
    CHECK(volume(cut) == Approx(exact).epsilon(1e-9).margin(1e-12));
    nonempty += exact > 0.01 ? 1 : 0;
  }
  CHECK(nonempty > 200);  // the trials do exercise real polyhedra
}

TEMPLATE_TEST_CASE("Repeated slicing: rotated boxes in 5D and 6D cut down to 3D match the exact section volume",
                   "[slicer]", D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(7 + N);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.35 + 0.05 * i;
  const DisplayMesh<N> mesh = display_mesh(Shape<N>::box(h), 1);
  BodySlicer<N> slicer(mesh);
  // Axis-aligned: the plain cube of the first three half-extents.
  std::array<double, std::size_t(N - 3)> zeros{};
  const DisplayMesh<3> cube = slicer.slice(Placement<N>{}, SliceChain<N>::axes(zeros));
  REQUIRE(closed_and_oriented(cube) == "");
  CHECK(volume(cube) == Approx(8 * h[0] * h[1] * h[2]).epsilon(1e-12));
  int nonempty = 0;
  for (int trial = 0; trial < 100; ++trial) {
    Placement<N> pl{random_rotation<N>(rng), Vec<N>::Zero()};
    for (int i = 0; i < N; ++i) pl.translation[i] = 0.3 * u(rng);
    const SliceChain<N> chain = random_chain<N>(rng, 0.2);
    const DisplayMesh<3> cut = slicer.slice(pl, chain);
    const Flat3<N> flat = chain.flat();
    const double exact = slice_checks::box_section_volume<N>(h, pl.rotation, pl.translation, flat.origin, flat.frame);
    INFO("trial " << trial);
    REQUIRE(closed_and_oriented(cut) == "");
    CHECK(volume(cut) == Approx(exact).epsilon(1e-9).margin(1e-12));
    nonempty += exact > 0.001 ? 1 : 0;
  }
  CHECK(nonempty > 50);
}

TEMPLATE_TEST_CASE("Slicer: an n-ball cut by the default chain is a sphere of radius sqrt(r^2 - |w|^2)", "[slicer]",
                   D4, D5) {
  constexpr int N = TestType::value;
  const double r = 0.8;
  const int sub = N == 4 ? 6 : 3;
  const Shape<N> ball = Shape<N>::ball(r);
  const double r_in = slice_checks::inner_radius<N>(boundary_mesh<N>(ball, sub));
  REQUIRE(r_in > 0.8 * r);  // keeps rho_in real for every cut below
  BodySlicer<N> slicer(display_mesh<N>(ball, sub));
  for (double w : {0.0, 0.3, 0.55}) {
    std::array<double, std::size_t(N - 3)> ws{};
    ws[0] = w;
    if (N == 5) ws[std::size_t(N - 4)] = 0.1;  // a second cut in 5D
    double w2 = 0.0;
    for (double x : ws) w2 += x * x;
    const double rho = std::sqrt(r * r - w2), rho_in = std::sqrt(r_in * r_in - w2);
    const DisplayMesh<3> sphere = slicer.slice(Placement<N>{}, SliceChain<N>::axes(ws));
    INFO("w " << w << ", rho " << rho << ", rho_in " << rho_in);
    REQUIRE(closed_and_oriented(sphere) == "");
    for (const Vec<3>& v : sphere.vertices) {
      CHECK(v.norm() <= rho * (1 + 1e-12));
      CHECK(v.norm() >= rho_in * (1 - 1e-12));
    }
    CHECK(volume(sphere) <= 4.0 / 3.0 * M_PI * std::pow(rho, 3) * (1 + 1e-12));
    CHECK(volume(sphere) >= 4.0 / 3.0 * M_PI * std::pow(rho_in, 3) * (1 - 1e-12));
    CHECK(area(sphere) <= 4.0 * M_PI * rho * rho * (1 + 1e-12));
    CHECK(area(sphere) >= 4.0 * M_PI * rho_in * rho_in * (1 - 1e-12));
    // Smooth normals: radial to round-off after one cut. After a second cut (5D) the corner normals
    // being interpolated are unit vectors at points of different radii, so the result is radial only
    // up to the angle an edge of the intermediate 4D slice spans (< 0.1 rad at this level).
    for (std::size_t c = 0; c < sphere.cells.size(); ++c)
      for (int q = 0; q < 3; ++q) {
        const Vec<3> y = sphere.vertices[std::size_t(sphere.cells[c][std::size_t(q)])];
        if (N == 4)
          CHECK((sphere.normals[c][std::size_t(q)] - y.normalized()).norm() < 1e-12);
        else
          CHECK(sphere.normals[c][std::size_t(q)].dot(y.normalized()) > std::cos(0.1));
      }
  }
  // Planes that miss the ball give nothing.
  std::array<double, std::size_t(N - 3)> far{};
  far[0] = 1.01 * r;
  CHECK(slicer.slice(Placement<N>{}, SliceChain<N>::axes(far)).empty());
  far[0] = -1.01 * r;
  CHECK(slicer.slice(Placement<N>{}, SliceChain<N>::axes(far)).empty());
}

TEST_CASE("Slicer: a finer 4-ball's slice area converges to the sphere's", "[slicer]") {
  // The area error of an inscribed tessellation falls with the square of the cell size.
  const double r = 1.0, w = 0.4, exact = 4 * M_PI * (r * r - w * w);
  double previous = INFINITY;
  for (int sub : {2, 4, 8}) {
    MeshSlicer<4> slicer(display_mesh(Shape<4>::ball(r), sub));
    const double err = std::abs(area(slicer.slice(Placement<4>{}, Hyperplane<4>::axis(w))) - exact) / exact;
    INFO("subdivisions " << sub << ", relative error " << err);
    CHECK(err < previous / 2.5);  // ~4x per halving (second order), 2.5x allows for the grid's anisotropy
    previous = err;
  }
  CHECK(previous < 0.02);  // and small in absolute terms at the level wedge render uses (8)
}

TEST_CASE("Slicer: closed and outward for thousands of random orientations and offsets", "[slicer]") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec<4>> points;
  for (int i = 0; i < 40; ++i) points.push_back(Vec<4>{u(rng), u(rng), u(rng), u(rng)} * 0.6);
  const std::vector<Shape<4>> shapes = {Shape<4>::box(Vec<4>(0.5, 0.2, 0.6, 0.4)), Shape<4>::ball(0.6),
                                        Shape<4>::duocylinder(0.5, 0.3), Shape<4>::spherinder(0.4, 0.3),
                                        Shape<4>::polytope(points)};
  int slices = 0, nonempty = 0;
  for (const Shape<4>& shape : shapes) {
    MeshSlicer<4> slicer(display_mesh(shape, 3));
    for (int trial = 0; trial < 600; ++trial) {
      Placement<4> pl{random_rotation<4>(rng), Vec<4>{u(rng), u(rng), u(rng), 0.5 * u(rng)}};
      const Hyperplane<4> plane = random_plane<4>(rng, [&] { return 0.5 * u(rng); });
      const DisplayMesh<3> cut = slicer.slice(pl, plane);
      ++slices;
      INFO("shape " << &shape - shapes.data() << ", trial " << trial);
      REQUIRE(closed_and_oriented(cut) == "");
      if (!cut.empty()) {
        ++nonempty;
        CHECK(volume(cut) > 0.0);
      }
    }
  }
  CHECK(slices == 3000);
  CHECK(nonempty > 1500);
}

TEST_CASE("Slicer: every straddling cell gives its pieces, skipped runs of cells included", "[slicer]") {
  // Brute force: a tetrahedron with k of its 4 vertices below the plane (distance < 0) and 4 - k above is
  // cut in a triangle (k = 1, 3) or a quad of two triangles (k = 2). The slicer skips runs of cells whose
  // bounding ball the plane misses; the count must still be exact, plane after plane, including planes
  // grazing the mesh and planes through its vertices.
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Shape<4>& shape : {Shape<4>::ball(0.6), Shape<4>::duocylinder(0.5, 0.3)}) {
    const DisplayMesh<4> mesh = display_mesh(shape, 8);
    MeshSlicer<4> slicer(mesh);
    for (int trial = 0; trial < 200; ++trial) {
      const Placement<4> pl{random_rotation<4>(rng), Vec<4>{u(rng), u(rng), u(rng), 0.3 * u(rng)}};
      Hyperplane<4> plane = random_plane<4>(rng, [&] { return 0.7 * u(rng); });
      if (trial % 10 == 0)  // through a vertex
        plane.offset = plane.normal.dot(pl.rotation * mesh.vertices[std::size_t(trial) % mesh.vertices.size()] +
                                        pl.translation);
      // The distance as the slicer rounds it, (R^T n).x + (n.p - d) summed in axis order, so that a vertex
      // on the plane falls on the same side in both.
      const Vec<4> a = pl.rotation.transpose() * plane.normal;
      const double b = plane.normal.dot(pl.translation) - plane.offset;
      std::size_t expected = 0;
      for (const auto& cell : mesh.cells) {
        int below = 0;
        for (int v : cell) {
          double d = b;
          for (int k = 0; k < 4; ++k) d += a[k] * mesh.vertices[std::size_t(v)][k];
          below += d < 0.0;
        }
        expected += below == 2 ? 2 : (below == 1 || below == 3 ? 1 : 0);
      }
      INFO("trial " << trial);
      CHECK(slicer.slice(pl, plane).cells.size() == expected);
    }
  }
}

TEST_CASE("Slicer: a 3D cube cut by a plane is a closed counter-clockwise square", "[slicer]") {
  MeshSlicer<3> slicer(display_mesh(Shape<3>::box(Vec<3>(0.5, 0.5, 0.5)), 2));
  const DisplayMesh<2> sq = slicer.slice(Placement<3>{}, Hyperplane<3>::axis(0.1));
  double signed_area = 0.0, perimeter = 0.0;
  std::map<int, int> out_deg, in_deg;
  for (const auto& seg : sq.cells) {
    const Vec<2> a = sq.vertices[std::size_t(seg[0])], b = sq.vertices[std::size_t(seg[1])];
    signed_area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    perimeter += (b - a).norm();
    ++out_deg[seg[0]];
    ++in_deg[seg[1]];
  }
  for (const auto& [v, d] : out_deg) CHECK((d == 1 && in_deg[v] == 1));
  CHECK(signed_area == Approx(1.0).epsilon(1e-12));
  CHECK(perimeter == Approx(4.0).epsilon(1e-12));
}

TEST_CASE("Hyperplane: through() gives a right-handed orthonormal frame", "[slicer]") {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec<4> n = trial == 0 ? Vec<4>(Vec<4>::Unit(3)) : trial == 1 ? Vec<4>(-Vec<4>::Unit(3)) : random_unit<4>(rng);
    const Hyperplane<4> h = Hyperplane<4>::through(2.0 * n, 1.0);
    Mat<4> m;
    m << h.frame, h.normal;
    CHECK((m.transpose() * m - Mat<4>::Identity()).norm() < 1e-14);
    CHECK(m.determinant() == Approx(1.0).epsilon(1e-14));
    CHECK((h.normal - n).norm() < 1e-14);
    CHECK(h.offset == Approx(0.5));
    if (trial == 0) CHECK(h.frame == Hyperplane<4>::axis(0.0).frame);
  }
  CHECK_THROWS_AS(Hyperplane<4>::through(Vec<4>::Zero(), 0.0), wedge::Error);
}
