// Shape objects of scene and inertia files -> Shape<N>; explicitly instantiated for N = 2..6.
//
//   {"type": "box", "half_extents": [n]}            {"type": "sphere" | "ball", "radius": r}
//   {"type": "polytope", "vertices": [[n], ..]}     {"type": "mesh", "vertices": [[n], ..], "cells": [[n ints], ..]}
//   {"type": "halfspace", "normal": [n], "offset": d}
//   {"type": "cylinder" | "cubinder" | "spherinder", "radius": r, "half_length": h}
//   {"type": "duocylinder", "radii": [r1, r2], "half_length": h (5D, 6D only)}
//   {"type": "round_product", "factors": [{"axes": [..], "radius": r} | {"axes": [a], "half_length": h}, ..]}
//   {"type": "regular_polytope", "polytope": "5-cell" | "tesseract" | .., "circumradius": R}   (4D only)
// Sizes, meshes and hulls are validated by the Shape constructors (wedge::Error); sizes and index
// ranges of the JSON itself are checked here, with paths.
#include <limits>

#include "wedge/scenes/scene.hpp"
#include "wedge/error.hpp"
#include "wedge/regular_polytopes.hpp"

namespace wedge::scenes {

namespace {

constexpr const char* kShapeTypes =
    "box, sphere, ball, polytope, mesh, halfspace, cylinder, cubinder, spherinder, duocylinder, round_product, "
    "regular_polytope";

template <int N>
std::vector<Vec<N>> read_points(const Node& node) {
  std::vector<Vec<N>> points;
  for (const Node& p : node.array()) points.push_back(p.vec<N>());
  return points;
}

int read_index(const Node& node, int limit, const char* what) {
  const std::int64_t i = node.integer();
  if (i < 0 || i >= limit)
    node.fail(std::string(what) + " " + std::to_string(i) + " out of range (0.." + std::to_string(limit - 1) + ")");
  return int(i);
}

template <int N>
SimplexMesh<N> read_mesh(ObjectReader& obj) {
  SimplexMesh<N> mesh;
  mesh.vertices = read_points<N>(obj.required("vertices"));
  const int count = int(std::min<std::size_t>(mesh.vertices.size(), std::numeric_limits<int>::max()));
  for (const Node& cell : obj.required("cells").array()) {
    std::array<int, N> c{};
    const std::vector<Node> idx = cell.array(N, "vertex indices");
    for (int k = 0; k < N; ++k) c[k] = read_index(idx[k], count, "vertex index");
    mesh.cells.push_back(c);
  }
  return mesh;
}

std::vector<ProductFactor> read_factors(const Node& node, int n) {
  std::vector<ProductFactor> factors;
  for (const Node& f : node.array()) {
    ObjectReader obj(f);
    const Node axes_node = obj.required("axes");
    std::vector<int> axes;
    for (const Node& a : axes_node.array()) axes.push_back(read_index(a, n, "axis"));
    const std::optional<Node> radius = obj.optional("radius");
    const std::optional<Node> half_length = obj.optional("half_length");
    obj.finish();
    if (bool(radius) == bool(half_length))
      f.fail("a factor has either \"radius\" (a ball over its axes) or \"half_length\" (an interval)");
    if (radius) {
      factors.push_back(ProductFactor::ball(std::move(axes), radius->number()));
    } else {
      if (axes.size() != 1) axes_node.fail("an interval factor has exactly one axis");
      factors.push_back(ProductFactor::interval(axes[0], half_length->number()));
    }
  }
  return factors;
}

template <int N>
Shape<N> read_shape_object(ObjectReader& obj, const Node& type_node, const std::string& type) {
  if (type == "box") return Shape<N>::box(obj.required("half_extents").vec<N>());
  if (type == "sphere" || type == "ball") return Shape<N>::ball(obj.required("radius").number());
  if (type == "polytope") {
    const Node v = obj.required("vertices");
    std::vector<Vec<N>> points = read_points<N>(v);
    if (int(points.size()) < N + 1)
      v.fail("a polytope needs at least " + std::to_string(N + 1) + " points in " + std::to_string(N) + "D, got " +
             std::to_string(points.size()));
    return Shape<N>::polytope(std::move(points));
  }
  if (type == "mesh") return Shape<N>::mesh(read_mesh<N>(obj));
  if (type == "halfspace") {
    const Vec<N> normal = obj.required("normal").vec<N>();
    return Shape<N>::halfspace(normal, obj.required("offset").number());
  }
  if (type == "cylinder" || type == "cubinder" || type == "spherinder") {
    const int min_dim = type == "cylinder" ? 3 : 4;
    if (N < min_dim)
      type_node.fail("a " + type + " needs at least " + std::to_string(min_dim) + " dimensions (this scene is " +
                     std::to_string(N) + "D)");
    const double r = obj.required("radius").number();
    const double h = obj.required("half_length").number();
    if (type == "cylinder") return Shape<N>::cylinder(r, h);
    if (type == "cubinder") return Shape<N>::cubinder(r, h);
    return Shape<N>::spherinder(r, h);
  }
  if (type == "duocylinder") {
    if (N < 4) type_node.fail("a duocylinder needs at least 4 dimensions (this scene is " + std::to_string(N) + "D)");
    const std::vector<double> radii = obj.required("radii").numbers(2);
    double h = 0.0;
    if (N > 4) {
      h = obj.required("half_length").number();
    } else if (obj.has("half_length")) {
      obj.optional("half_length")->fail("a 4D duocylinder has no free axis: no \"half_length\"");
    }
    return Shape<N>::duocylinder(radii[0], radii[1], h);
  }
  if (type == "round_product") return Shape<N>::round_product(read_factors(obj.required("factors"), N));
  if (type == "regular_polytope") {
    if constexpr (N == 4) {
      const Node name_node = obj.required("polytope");
      const std::string name = name_node.string();
      const std::optional<RegularPolytope4> which = parse_regular_polytope(name);
      if (!which) name_node.fail("unknown regular polytope \"" + name + "\" (known: " + regular_polytope_names() + ")");
      const Node radius_node = obj.required("circumradius");
      const double radius = radius_node.number();
      if (!(radius > 0.0)) radius_node.fail("the circumradius must be positive (m)");
      return regular_polytope_shape(*which, radius);
    } else {
      type_node.fail("regular polytopes exist only in 4D here (this scene is " + std::to_string(N) + "D)");
    }
  }
  type_node.fail("unknown shape type \"" + type + "\" (known: " + kShapeTypes + ")");
}

}  // namespace

template <int N>
Shape<N> read_shape(const Node& node) {
  ObjectReader obj(node);
  const Node type_node = obj.required("type");
  const std::string type = type_node.string();
  std::optional<Shape<N>> shape;
  try {
    shape.emplace(read_shape_object<N>(obj, type_node, type));
  } catch (const Error& e) {
    throw JsonError(node.path(), e.what());
  }
  obj.finish();  // after the reading: only then are the keys of this type known
  return std::move(*shape);
}

template Shape<2> read_shape<2>(const Node&);
template Shape<3> read_shape<3>(const Node&);
template Shape<4> read_shape<4>(const Node&);
template Shape<5> read_shape<5>(const Node&);
template Shape<6> read_shape<6>(const Node&);

}  // namespace wedge::scenes
