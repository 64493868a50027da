#include "wedge/shape.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "wedge/error.hpp"

namespace wedge {
namespace {

void require_size(double v, const char* what) {
  if (!(std::isfinite(v) && v > 0.0)) {
    std::ostringstream s;
    s << what << " must be positive and finite (got " << v << ")";
    throw Error(s.str());
  }
}

std::vector<int> axis_range(int from, int to) {
  std::vector<int> a;
  for (int i = from; i < to; ++i) a.push_back(i);
  return a;
}

template <int N>
void require_dimension(int min_n, const char* name) {
  if (N < min_n)
    throw Error(std::string(name) + " needs at least " + std::to_string(min_n) + " dimensions (this is " +
                std::to_string(N) + "D)");
}

}  // namespace

template <int N>
Shape<N>::Shape(shapes::Box<N> box) : value_(box) {
  for (int i = 0; i < N; ++i) {
    const std::string what = "box half-extent " + std::to_string(i);
    require_size(box.half_extents[i], what.c_str());
  }
  features_ = std::make_shared<const ConvexFeatures<N>>(box_features<N>(box.half_extents));
}

template <int N>
Shape<N>::Shape(shapes::Ball<N> ball) : value_(ball) {
  require_size(ball.radius, "ball radius");
}

template <int N>
Shape<N>::Shape(shapes::Polytope<N> polytope) {
  try {
    hull_ = std::make_shared<const ConvexHull<N>>(convex_hull<N>(polytope.vertices));
    features_ = std::make_shared<const ConvexFeatures<N>>(convex_features<N>(*hull_));
  } catch (const Error& e) {
    throw Error(std::string("polytope: ") + e.what());
  }
  value_ = std::move(polytope);
}

template <int N>
Shape<N>::Shape(shapes::Mesh<N> mesh) {
  validate(mesh.mesh);
  features_ = std::make_shared<const ConvexFeatures<N>>(convex_features<N>(convex_hull<N>(mesh.mesh.vertices)));
  value_ = std::move(mesh);
}

template <int N>
Shape<N>::Shape(shapes::Halfspace<N> h) {
  if (!all_finite(h.normal) || !std::isfinite(h.offset)) throw Error("half-space normal and offset must be finite");
  const double len = h.normal.norm();
  if (!(len > 1e-12)) throw Error("half-space normal must be non-zero (it is normalised to unit length)");
  h.normal /= len;
  h.offset /= len;
  value_ = h;
}

template <int N>
Shape<N>::Shape(shapes::RoundProduct<N> product) {
  validate_factors<N>(product.factors);
  value_ = std::move(product);
}

template <int N>
Shape<N> Shape<N>::cylinder(double radius, double half_length) {
  require_dimension<N>(3, "a cylinder");
  std::vector<ProductFactor> f{ProductFactor::ball({0, 1}, radius)};
  for (int a = 2; a < N; ++a) f.push_back(ProductFactor::interval(a, half_length));
  return round_product(std::move(f));
}

template <int N>
Shape<N> Shape<N>::cubinder(double radius, double half_length) {
  require_dimension<N>(4, "a cubinder");
  return cylinder(radius, half_length);
}

template <int N>
Shape<N> Shape<N>::spherinder(double radius, double half_length) {
  require_dimension<N>(4, "a spherinder");
  std::vector<ProductFactor> f{ProductFactor::ball(axis_range(0, 3), radius)};
  for (int a = 3; a < N; ++a) f.push_back(ProductFactor::interval(a, half_length));
  return round_product(std::move(f));
}

template <int N>
Shape<N> Shape<N>::duocylinder(double radius1, double radius2, double half_length) {
  require_dimension<N>(4, "a duocylinder");
  std::vector<ProductFactor> f{ProductFactor::ball({0, 1}, radius1), ProductFactor::ball({2, 3}, radius2)};
  for (int a = 4; a < N; ++a) f.push_back(ProductFactor::interval(a, half_length));
  return round_product(std::move(f));
}

template <int N>
const ConvexHull<N>& Shape<N>::hull() const {
  if (!hull_) throw Error("shape is not a polytope: it has no convex hull");
  return *hull_;
}

template <int N>
SimplexMesh<N> boundary_mesh(const Shape<N>& shape, int subdivisions) {
  return std::visit(
      [&](const auto& s) -> SimplexMesh<N> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, shapes::Box<N>>) {
          return box_mesh<N>(s.half_extents, subdivisions);
        } else if constexpr (std::is_same_v<T, shapes::Ball<N>>) {
          return ball_mesh<N>(s.radius, subdivisions);
        } else if constexpr (std::is_same_v<T, shapes::Polytope<N>>) {
          return shape.hull().mesh;
        } else if constexpr (std::is_same_v<T, shapes::Mesh<N>>) {
          return s.mesh;
        } else if constexpr (std::is_same_v<T, shapes::RoundProduct<N>>) {
          return round_product_mesh<N>(s.factors, subdivisions);
        } else {
          throw Error("a half-space is unbounded: it has no boundary mesh");
        }
      },
      shape.description());
}

template struct Shape<2>;
template struct Shape<3>;
template struct Shape<4>;
template struct Shape<5>;
template struct Shape<6>;
template SimplexMesh<2> boundary_mesh<2>(const Shape<2>&, int);
template SimplexMesh<3> boundary_mesh<3>(const Shape<3>&, int);
template SimplexMesh<4> boundary_mesh<4>(const Shape<4>&, int);
template SimplexMesh<5> boundary_mesh<5>(const Shape<5>&, int);
template SimplexMesh<6> boundary_mesh<6>(const Shape<6>&, int);

}  // namespace wedge
