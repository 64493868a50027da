// Shapes (wedge/shape.hpp): every constructor validates its description and refuses bad input with a
// message naming the problem; named round products have the documented factors; boundary meshes of
// every bounded kind are valid, and the half-space is normalised and unbounded.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "wedge/error.hpp"
#include "wedge/shape.hpp"

namespace {

using wedge::ProductFactor;
using wedge::Shape;
using wedge::Vec;
namespace shapes = wedge::shapes;

template <int N>
std::vector<ProductFactor> factors_of(const Shape<N>& s) {
  return s.template as<shapes::RoundProduct<N>>().factors;
}

}  // namespace

TEST_CASE("Shapes hold their validated description", "[shape]") {
  const Shape<3> box = Shape<3>::box(Vec<3>(1, 2, 3));
  CHECK(box.is<shapes::Box<3>>());
  CHECK(box.as<shapes::Box<3>>().half_extents == Vec<3>(1, 2, 3));
  CHECK(box.bounded());
  const Shape<4> ball = Shape<4>::ball(0.5);
  CHECK(ball.as<shapes::Ball<4>>().radius == 0.5);
  const Shape<2> half = Shape<2>::halfspace(Vec<2>(0, 3), 6.0);
  CHECK_FALSE(half.bounded());
  CHECK(half.as<shapes::Halfspace<2>>().normal == Vec<2>(0, 1));  // normalised with its offset
  CHECK(half.as<shapes::Halfspace<2>>().offset == 2.0);
  const Shape<3> poly = Shape<3>::polytope({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0, 0, 1),
                                            Vec<3>(0.1, 0.1, 0.1)});
  CHECK(poly.as<shapes::Polytope<3>>().vertices.size() == 5);  // the description as given
  CHECK(poly.hull().mesh.vertices.size() == 4);                // the hull without the interior point
  REQUIRE_THROWS_WITH(box.hull(), Catch::Contains("not a polytope"));
  const Shape<3> mesh = Shape<3>::mesh(wedge::box_mesh<3>(Vec<3>::Ones(), 2));
  CHECK(mesh.as<shapes::Mesh<3>>().mesh.cells.size() == 48);
  // Copies share the hull.
  const Shape<3> copy = poly;
  CHECK(&copy.hull() == &poly.hull());
}

TEST_CASE("Named round products", "[shape]") {
  using K = ProductFactor::Kind;
  {
    const auto f = factors_of<3>(Shape<3>::cylinder(0.5, 2.0));
    REQUIRE(f.size() == 2);
    CHECK((f[0].axes == std::vector<int>{0, 1} && f[0].kind == K::Ball && f[0].size == 0.5));
    CHECK((f[1].axes == std::vector<int>{2} && f[1].kind == K::Interval && f[1].size == 2.0));
  }
  {
    const auto f = factors_of<4>(Shape<4>::cubinder(0.5, 2.0));
    REQUIRE(f.size() == 3);
    CHECK((f[1].axes == std::vector<int>{2} && f[2].axes == std::vector<int>{3}));
  }
  {
    const auto f = factors_of<4>(Shape<4>::spherinder(0.5, 2.0));
    REQUIRE(f.size() == 2);
    CHECK((f[0].axes == std::vector<int>{0, 1, 2} && f[0].kind == K::Ball));
    CHECK((f[1].axes == std::vector<int>{3} && f[1].kind == K::Interval));
  }
  {
    const auto f = factors_of<4>(Shape<4>::duocylinder(0.5, 0.7));
    REQUIRE(f.size() == 2);
    CHECK((f[0].axes == std::vector<int>{0, 1} && f[1].axes == std::vector<int>{2, 3} && f[1].size == 0.7));
    const auto g = factors_of<5>(Shape<5>::duocylinder(0.5, 0.7, 0.2));
    REQUIRE(g.size() == 3);
    CHECK((g[2].axes == std::vector<int>{4} && g[2].size == 0.2));
  }
  REQUIRE_THROWS_WITH(Shape<2>::cylinder(1, 1), Catch::Contains("a cylinder needs at least 3 dimensions"));
  REQUIRE_THROWS_WITH(Shape<3>::spherinder(1, 1), Catch::Contains("a spherinder needs at least 4 dimensions"));
  REQUIRE_THROWS_WITH(Shape<3>::duocylinder(1, 1), Catch::Contains("a duocylinder needs at least 4 dimensions"));
  REQUIRE_THROWS_WITH(Shape<3>::cubinder(1, 1), Catch::Contains("a cubinder needs at least 4 dimensions"));
  REQUIRE_THROWS_WITH(Shape<5>::duocylinder(1, 1), Catch::Contains("half-length"));  // the 5th axis needs one
}

TEST_CASE("Shape constructors refuse invalid descriptions", "[shape]") {
  REQUIRE_THROWS_WITH(Shape<3>::box(Vec<3>(1, 0, 1)), Catch::Contains("box half-extent 1 must be positive"));
  REQUIRE_THROWS_WITH(Shape<3>::box(Vec<3>(-1, 1, 1)), Catch::Contains("box half-extent 0 must be positive"));
  REQUIRE_THROWS_WITH(Shape<3>::box(Vec<3>(1, 1, INFINITY)), Catch::Contains("box half-extent 2 must be positive and finite"));
  REQUIRE_THROWS_WITH(Shape<4>::ball(0.0), Catch::Contains("ball radius must be positive"));
  REQUIRE_THROWS_WITH(Shape<4>::ball(-1.0), Catch::Contains("ball radius must be positive"));
  REQUIRE_THROWS_WITH(Shape<4>::ball(NAN), Catch::Contains("ball radius must be positive"));
  REQUIRE_THROWS_WITH(Shape<3>::halfspace(Vec<3>::Zero(), 1.0), Catch::Contains("normal must be non-zero"));
  REQUIRE_THROWS_WITH(Shape<3>::halfspace(Vec<3>(0, NAN, 1), 1.0), Catch::Contains("must be finite"));
  REQUIRE_THROWS_WITH(Shape<3>::cylinder(0.0, 1.0), Catch::Contains("non-positive or non-finite radius"));
  REQUIRE_THROWS_WITH(Shape<3>::cylinder(1.0, -1.0), Catch::Contains("non-positive or non-finite half-length"));
  REQUIRE_THROWS_WITH(Shape<4>::round_product({ProductFactor::ball({0, 1}, 1.0), ProductFactor::ball({1, 2, 3}, 1.0)}),
                      Catch::Contains("axis 1 appears in factors 0 and 1"));
  REQUIRE_THROWS_WITH(Shape<4>::round_product({ProductFactor::ball({0, 1, 2}, 1.0)}), Catch::Contains("axis 3 is not covered"));
  // Polytopes: degenerate point sets, named as such.
  REQUIRE_THROWS_WITH(Shape<3>::polytope({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(2, 0, 0), Vec<3>(3, 0, 0)}),
                      Catch::Contains("polytope: convex hull: the points are flat"));
  REQUIRE_THROWS_WITH(Shape<3>::polytope({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0)}), Catch::Contains("needs at least 4 points"));
  REQUIRE_THROWS_WITH(Shape<2>::polytope(std::vector<Vec<2>>(5, Vec<2>(1, 1))), Catch::Contains("coincide"));
  // Meshes are validated.
  auto open = wedge::box_mesh<4>(Vec<4>::Ones(), 1);
  open.cells.pop_back();
  REQUIRE_THROWS_WITH(Shape<4>::mesh(open), Catch::Contains("open mesh"));
  auto inside_out = wedge::box_mesh<3>(Vec<3>::Ones(), 1);
  for (auto& c : inside_out.cells) std::swap(c[0], c[1]);
  REQUIRE_THROWS_WITH(Shape<3>::mesh(inside_out), Catch::Contains("inside-out"));
}

TEST_CASE("boundary_mesh of every bounded kind is a valid closed mesh", "[shape]") {
  const std::vector<Shape<4>> kinds = {
      Shape<4>::box(Vec<4>(1, 2, 3, 4)),
      Shape<4>::ball(1.5),
      Shape<4>::polytope(wedge::box_mesh<4>(Vec<4>::Ones(), 1).vertices),
      Shape<4>::mesh(wedge::box_mesh<4>(Vec<4>::Ones(), 2)),
      Shape<4>::spherinder(1.0, 0.5),
      Shape<4>::duocylinder(1.0, 0.5),
      Shape<4>::cubinder(1.0, 0.5),
  };
  for (const Shape<4>& s : kinds) {
    const auto m = wedge::boundary_mesh<4>(s, 3);
    CHECK_NOTHROW(wedge::validate(m));
  }
  CHECK(wedge::boundary_mesh<4>(kinds[0], 3).cells.size() == std::size_t(wedge::box_mesh_cell_count(4, 3)));
  CHECK(wedge::boundary_mesh<4>(kinds[1]).cells.size() ==
        std::size_t(wedge::box_mesh_cell_count(4, wedge::default_subdivisions(4))));
  REQUIRE_THROWS_WITH(wedge::boundary_mesh<4>(Shape<4>::halfspace(Vec<4>::Unit(3), 0.0)), Catch::Contains("unbounded"));
}
