// The shapes a scene can give a body: box, ball, convex polytope (hull of points), closed simplicial
// mesh, half-space (static ground/walls) and round products (cylinder, spherinder, duocylinder, ..).
// A Shape is validated when it is created, so every Shape in existence describes a proper solid.
#pragma once

#include <memory>
#include <utility>
#include <variant>
#include <vector>

#include "wedge/collision/detail/convex_features.hpp"
#include "wedge/ga/types.hpp"
#include "wedge/hull.hpp"
#include "wedge/mesh.hpp"

namespace wedge {
namespace shapes {

// The box [-h, h], centred at the origin.
template <int N>
struct Box {
  Vec<N> half_extents;
};
// The n-ball of the given radius, centred at the origin.
template <int N>
struct Ball {
  double radius = 0.0;
};
// The convex hull of the points (which need not all be extreme).
template <int N>
struct Polytope {
  std::vector<Vec<N>> vertices;
};
// A closed outward simplicial boundary mesh (see mesh.hpp); it need not be convex.
template <int N>
struct Mesh {
  SimplexMesh<N> mesh;
};
// The points x with normal . x <= offset; normal has unit length. Infinite: for static bodies only.
template <int N>
struct Halfspace {
  Vec<N> normal;
  double offset = 0.0;
};
// The product of balls and intervals over a partition of the axes, centred at the origin.
template <int N>
struct RoundProduct {
  std::vector<ProductFactor> factors;
};

}  // namespace shapes

template <int N>
struct Shape {
  using Variant = std::variant<shapes::Box<N>, shapes::Ball<N>, shapes::Polytope<N>, shapes::Mesh<N>,
                               shapes::Halfspace<N>, shapes::RoundProduct<N>>;

  // Each constructor validates and throws wedge::Error for non-positive or non-finite sizes, a zero
  // normal, factors that do not partition the axes, a degenerate point set or an invalid mesh. The
  // half-space normal and offset are divided by the normal's length.
  Shape(shapes::Box<N> box);
  Shape(shapes::Ball<N> ball);
  Shape(shapes::Polytope<N> polytope);
  Shape(shapes::Mesh<N> mesh);
  Shape(shapes::Halfspace<N> halfspace);
  Shape(shapes::RoundProduct<N> product);

  static Shape box(const Vec<N>& half_extents) { return Shape(shapes::Box<N>{half_extents}); }
  static Shape ball(double radius) { return Shape(shapes::Ball<N>{radius}); }
  static Shape polytope(std::vector<Vec<N>> points) { return Shape(shapes::Polytope<N>{std::move(points)}); }
  static Shape mesh(SimplexMesh<N> mesh) { return Shape(shapes::Mesh<N>{std::move(mesh)}); }
  static Shape halfspace(const Vec<N>& normal, double offset) { return Shape(shapes::Halfspace<N>{normal, offset}); }
  static Shape round_product(std::vector<ProductFactor> factors) {
    return Shape(shapes::RoundProduct<N>{std::move(factors)});
  }
  // Named round products; the remaining axes are intervals [-half_length, half_length]:
  //   cylinder    disk on axes {0,1} x intervals            (N >= 3; the 3D cylinder)
  //   cubinder    the same, under its 4D name                (N >= 4)
  //   spherinder  3-ball on axes {0,1,2} x intervals         (N >= 4)
  //   duocylinder disk on {0,1} x disk on {2,3} x intervals  (N >= 4; half_length unused in 4D)
  static Shape cylinder(double radius, double half_length);
  static Shape cubinder(double radius, double half_length);
  static Shape spherinder(double radius, double half_length);
  static Shape duocylinder(double radius1, double radius2, double half_length = 0.0);

  const Variant& description() const { return value_; }
  template <class T>
  bool is() const {
    return std::holds_alternative<T>(value_);
  }
  template <class T>
  const T& as() const {
    return std::get<T>(value_);
  }
  // False only for the half-space.
  bool bounded() const { return !is<shapes::Halfspace<N>>(); }
  // The convex hull of a Polytope, computed when the shape was created; throws for other kinds.
  const ConvexHull<N>& hull() const;
  // The face lattice for collision detection: set for boxes, polytopes and meshes (a mesh collides as
  // its convex hull), null for balls, round products and half-spaces.
  const ConvexFeatures<N>* features() const { return features_.get(); }

 private:
  Variant value_;
  std::shared_ptr<const ConvexHull<N>> hull_;
  std::shared_ptr<const ConvexFeatures<N>> features_;
};

// A boundary mesh of a bounded shape (box, ball and round products tessellated at `subdivisions`,
// see mesh.hpp; a polytope's hull and a mesh as they are). Throws wedge::Error for a half-space.
template <int N>
SimplexMesh<N> boundary_mesh(const Shape<N>& shape, int subdivisions = default_subdivisions(N));

}  // namespace wedge
