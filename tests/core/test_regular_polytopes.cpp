// The six regular 4-polytopes (wedge/regular_polytopes.hpp) against their known combinatorics and
// metric: vertex counts, cell counts from Qhull, all vertices on the circumsphere, one edge length with
// the known number of edges, the known edge/circumradius ratio, and the 4-volume three ways (the closed
// form, the covariance method on the hull, and the pyramid sum over the cells: V = (1/4) cells x cell
// volume x inradius with the cells' closed-form 3-volumes).
//
// Sources for the closed forms (edge a, circumradius R):
//   Coxeter, Regular Polytopes (3rd ed., 1973), table I (i) p. 292-293: a/R = sqrt(5/2) {3,3,3},
//   1 {4,3,3}, sqrt2 {3,3,4}, 1 {3,4,3}, 1/(phi^2 sqrt2) {5,3,3}, 1/phi {3,3,5}; vertex, edge and cell
//   counts N0, N1, N3 in table I (ii).
//   4-volumes: 5-cell sqrt5 a^4 / 96, tesseract a^4, 16-cell a^4 / 6, 24-cell 2 a^4,
//   120-cell (15/4)(105 + 47 sqrt5) a^4, 600-cell (25/4)(2 + sqrt5) a^4 (the "4-content" entries of the
//   Wikipedia articles on each polytope, which cite Coxeter; the pyramid sum below checks them
//   independently).
//   Cell 3-volumes: tetrahedron a^3 / (6 sqrt2), cube a^3, octahedron sqrt2 a^3 / 3, dodecahedron
//   (15 + 7 sqrt5) a^3 / 4.
//
// Tolerances: the coordinates are exact up to one rounding of phi, sqrt5 and the scale, so radii and
// edges match to 1e-14 relative; we allow 1e-12. Edges are told from the next-shortest distance (at
// least 1.17 a, in the 600-cell: 2 sin 36 deg vs 2 sin 18 deg) with a 1e-9 relative band. Volumes sum
// up to 14,400 simplices (the 120-cell), accumulated round-off stays below 1e-13 relative; 1e-10.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "wedge/error.hpp"
#include "wedge/hull.hpp"
#include "wedge/mass.hpp"
#include "wedge/regular_polytopes.hpp"

namespace {

using wedge::RegularPolytope4;
using wedge::Vec;

const double kPhi = (1.0 + std::sqrt(5.0)) / 2.0;
const double kSqrt5 = std::sqrt(5.0);

struct Known {
  RegularPolytope4 which;
  const char* name;
  std::size_t vertices, edges, cells;
  double edge_over_radius;
  double volume_over_edge4;
  double cell_volume_over_edge3;
};

std::vector<Known> known() {
  const double tet = 1.0 / (6.0 * std::sqrt(2.0)), oct = std::sqrt(2.0) / 3.0, dodec = (15.0 + 7.0 * kSqrt5) / 4.0;
  return {
      {RegularPolytope4::Cell5, "5-cell", 5, 10, 5, std::sqrt(2.5), kSqrt5 / 96.0, tet},
      {RegularPolytope4::Cell8, "tesseract", 16, 32, 8, 1.0, 1.0, 1.0},
      {RegularPolytope4::Cell16, "16-cell", 8, 24, 16, std::sqrt(2.0), 1.0 / 6.0, tet},
      {RegularPolytope4::Cell24, "24-cell", 24, 96, 24, 1.0, 2.0, oct},
      {RegularPolytope4::Cell120, "120-cell", 600, 1200, 120, 1.0 / (kPhi * kPhi * std::sqrt(2.0)),
       15.0 / 4.0 * (105.0 + 47.0 * kSqrt5), dodec},
      {RegularPolytope4::Cell600, "600-cell", 120, 720, 600, 1.0 / kPhi, 25.0 / 4.0 * (2.0 + kSqrt5), tet},
  };
}

bool close_rel(double a, double b, double rel) { return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)); }

}  // namespace

TEST_CASE("Regular 4-polytopes: counts, circumsphere, edges, cells and volume", "[regular_polytopes]") {
  const double radius = 1.7;
  for (const Known& k : known()) {
    INFO(k.name);
    const std::vector<Vec<4>> v = wedge::regular_polytope_vertices(k.which, radius);
    REQUIRE(v.size() == k.vertices);
    Vec<4> sum = Vec<4>::Zero();
    for (const Vec<4>& p : v) {
      CHECK(close_rel(p.norm(), radius, 1e-12));
      sum += p;
    }
    CHECK(sum.norm() < 1e-12 * radius * double(v.size()));  // centred: symmetric under x -> -x or A4

    // Edges: the shortest pairwise distance, and how many pairs attain it.
    double shortest = INFINITY;
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = i + 1; j < v.size(); ++j) shortest = std::min(shortest, (v[i] - v[j]).norm());
    std::size_t edges = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = i + 1; j < v.size(); ++j) edges += (v[i] - v[j]).norm() <= shortest * (1 + 1e-9) ? 1 : 0;
    CHECK(edges == k.edges);
    const double a = k.edge_over_radius * radius;
    CHECK(close_rel(shortest, a, 1e-12));

    // Cells: Qhull's facets with coplanar points merged; every vertex is extreme.
    const wedge::ConvexHull<4> hull = wedge::convex_hull<4>(v);
    CHECK(hull.normals.size() == k.cells);
    CHECK(hull.mesh.vertices.size() == k.vertices);
    // Regular: every cell is at the same distance (the inradius) from the centre.
    double inradius = hull.offsets[0];
    for (double o : hull.offsets) CHECK(close_rel(o, inradius, 1e-12));

    const double volume = k.volume_over_edge4 * std::pow(a, 4);
    const double pyramids = 0.25 * double(k.cells) * k.cell_volume_over_edge3 * std::pow(a, 3) * inradius;
    CHECK(close_rel(pyramids, volume, 1e-10));
    const wedge::Shape<4> shape = wedge::regular_polytope_shape(k.which, radius);
    const wedge::MassProperties<4> props = wedge::mass_properties(shape, 1.0);
    CHECK(close_rel(props.volume, volume, 1e-10));
    CHECK(props.center.norm() < 1e-12 * radius);
    // Regular polytopes are isotropic: covariance = (m / 4) <|x|^2> I, a multiple of the identity.
    const double c = props.covariance.trace() / 4.0;
    CHECK((props.covariance - c * wedge::Mat<4>::Identity()).norm() < 1e-10 * c);
  }
}

TEST_CASE("Regular 4-polytopes: names parse, bad circumradius throws", "[regular_polytopes]") {
  for (const Known& k : known()) {
    CHECK(wedge::regular_polytope_name(k.which) == k.name);
    CHECK(wedge::parse_regular_polytope(k.name) == k.which);
  }
  CHECK(wedge::parse_regular_polytope("8-cell") == RegularPolytope4::Cell8);
  CHECK_FALSE(wedge::parse_regular_polytope("7-cell").has_value());
  CHECK_FALSE(wedge::parse_regular_polytope("Tesseract").has_value());
  CHECK(wedge::regular_polytope_names().find("600-cell") != std::string::npos);
  for (double r : {0.0, -1.0, double(INFINITY), double(NAN)})
    REQUIRE_THROWS_WITH(wedge::regular_polytope_vertices(RegularPolytope4::Cell24, r),
                        Catch::Contains("circumradius of a 24-cell must be positive and finite"));
}
