// Support functions, support sets and containment of every bounded shape, in the body frame.
#include <cmath>
#include <numbers>

#include "collision/narrow.hpp"
#include "wedge/error.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {
namespace {

// One factor's extreme point along d, written into its own axes of p.
template <int N>
void factor_support(const ProductFactor& f, const Vec<N>& d, Vec<N>& p) {
  if (f.kind == ProductFactor::Kind::Interval) {
    p[f.axes[0]] = d[f.axes[0]] < 0.0 ? -f.size : f.size;
    return;
  }
  double len2 = 0.0;
  for (int a : f.axes) len2 += d[a] * d[a];
  if (len2 > 0.0) {
    const double s = f.size / std::sqrt(len2);
    for (int a : f.axes) p[a] = d[a] * s;
  } else {
    p[f.axes[0]] = f.size;
  }
}

template <int N>
Vec<N> product_support(const std::vector<ProductFactor>& factors, const Vec<N>& d) {
  Vec<N> p = Vec<N>::Zero();
  for (const ProductFactor& f : factors) factor_support<N>(f, d, p);
  return p;
}

template <int N>
const std::vector<Vec<N>>& hull_vertices(const Shape<N>& shape) {
  return shape.features()->vertices;
}

}  // namespace

template <int N>
const std::vector<ProductFactor>& product_factors(const Shape<N>& shape) {
  if (shape.template is<shapes::RoundProduct<N>>()) return shape.template as<shapes::RoundProduct<N>>().factors;
  // A box is N intervals. The list is kept per thread and only its sizes change, so the query allocates
  // nothing after the first call.
  thread_local std::vector<ProductFactor> box;
  if (box.size() != std::size_t(N)) {
    box.clear();
    for (int i = 0; i < N; ++i) box.push_back(ProductFactor::interval(i, 0.0));
  }
  const Vec<N>& h = shape.template as<shapes::Box<N>>().half_extents;
  for (int i = 0; i < N; ++i) box[i].size = h[i];
  return box;
}

template <int N>
Vec<N> local_support(const Shape<N>& shape, const Vec<N>& d) {
  switch (kind_of(shape)) {
    case ShapeKind::Box: {
      const Vec<N>& h = shape.template as<shapes::Box<N>>().half_extents;
      Vec<N> p;
      for (int i = 0; i < N; ++i) p[i] = d[i] < 0.0 ? -h[i] : h[i];
      return p;
    }
    case ShapeKind::Ball: {
      const double r = shape.template as<shapes::Ball<N>>().radius;
      const double len = d.norm();
      return len > 0.0 ? Vec<N>(d * (r / len)) : Vec<N>(Vec<N>::Unit(0) * r);
    }
    case ShapeKind::RoundProduct:
      return product_support<N>(shape.template as<shapes::RoundProduct<N>>().factors, d);
    case ShapeKind::Polytope:
    case ShapeKind::Mesh: {
      const auto& v = hull_vertices(shape);
      int best = 0;
      double best_dot = v[0].dot(d);
      for (int i = 1; i < int(v.size()); ++i) {
        const double t = v[i].dot(d);
        if (t > best_dot) best_dot = t, best = i;
      }
      return v[best];
    }
    default:
      throw Error("support of an unbounded shape (half-space)");
  }
}

template <int N>
void local_support_set(const Shape<N>& shape, const Vec<N>& d, double tolerance, std::vector<SupportPoint<N>>& out) {
  out.clear();
  const Vec<N> u = d.normalized();
  const ShapeKind kind = kind_of(shape);
  if (kind == ShapeKind::Ball) {
    out.push_back({local_support(shape, u), 0});
    return;
  }
  if (kind == ShapeKind::Polytope || kind == ShapeKind::Mesh) {
    const auto& v = hull_vertices(shape);
    double top = -INFINITY;
    for (const Vec<N>& p : v) top = std::max(top, p.dot(u));
    for (int i = 0; i < int(v.size()); ++i)
      if (v[i].dot(u) >= top - tolerance) out.push_back({v[i], std::uint32_t(i)});
    return;
  }
  // Box or round product: the Cartesian product of each factor's extreme points along u. A factor
  // counts as orthogonal to u when tilting it over its whole size moves it by less than the tolerance.
  const std::vector<ProductFactor>& factors = product_factors(shape);
  out.push_back({Vec<N>::Zero(), 0});
  std::uint32_t radix = 1;
  thread_local std::vector<SupportPoint<N>> next;
  thread_local std::vector<Vec<N>> choices;  // this factor's contribution on its own axes
  for (const ProductFactor& f : factors) {
    double len2 = 0.0;
    for (int a : f.axes) len2 += u[a] * u[a];
    const bool flat = std::sqrt(len2) * f.size < tolerance;
    choices.clear();
    if (!flat) {
      Vec<N> p = Vec<N>::Zero();  // (no vector of one factor: that allocated on every call)
      factor_support<N>(f, u, p);
      choices.push_back(p);
    } else if (f.kind == ProductFactor::Kind::Interval) {
      choices.push_back(Vec<N>::Unit(f.axes[0]) * -f.size);
      choices.push_back(Vec<N>::Unit(f.axes[0]) * f.size);
    } else if (f.axes.size() == 2) {  // a flat disk: eight points on its rim
      for (int k = 0; k < 8; ++k) {
        const double t = k * std::numbers::pi / 4.0;
        Vec<N> p = Vec<N>::Zero();
        p[f.axes[0]] = f.size * std::cos(t);
        p[f.axes[1]] = f.size * std::sin(t);
        choices.push_back(p);
      }
    } else {  // a flat ball of 3 or more axes: its 2d axis points
      for (int a : f.axes) {
        choices.push_back(Vec<N>::Unit(a) * f.size);
        choices.push_back(Vec<N>::Unit(a) * -f.size);
      }
    }
    next.clear();
    for (const SupportPoint<N>& s : out)
      for (std::size_t c = 0; c < choices.size(); ++c)
        next.push_back({Vec<N>(s.point + choices[c]), s.id + radix * std::uint32_t(c)});
    radix *= std::uint32_t(choices.size());
    out.swap(next);
  }
}

template <int N>
bool local_contains(const Shape<N>& shape, const Vec<N>& x, double tol) {
  switch (kind_of(shape)) {
    case ShapeKind::Ball:
      return x.norm() <= shape.template as<shapes::Ball<N>>().radius + tol;
    case ShapeKind::Box:
    case ShapeKind::RoundProduct: {
      for (const ProductFactor& f : product_factors(shape)) {
        double len2 = 0.0;
        for (int a : f.axes) len2 += x[a] * x[a];
        if (std::sqrt(len2) > f.size + tol) return false;
      }
      return true;
    }
    case ShapeKind::Polytope:
    case ShapeKind::Mesh:
      for (const auto& facet : shape.features()->facets)
        if (facet.normal.dot(x) > facet.offset + tol) return false;
      return true;
    default: {
      const auto& h = shape.template as<shapes::Halfspace<N>>();
      return h.normal.dot(x) <= h.offset + tol;
    }
  }
}

template <int N>
double shape_scale(const Shape<N>& shape) {
  switch (kind_of(shape)) {
    case ShapeKind::Ball:
      return shape.template as<shapes::Ball<N>>().radius;
    case ShapeKind::Box:
      return shape.template as<shapes::Box<N>>().half_extents.norm();
    case ShapeKind::RoundProduct: {
      double s = 0.0;
      for (const ProductFactor& f : shape.template as<shapes::RoundProduct<N>>().factors) s += f.size * f.size;
      return std::sqrt(s);
    }
    case ShapeKind::Polytope:
    case ShapeKind::Mesh: {
      double s = 0.0;
      for (const Vec<N>& v : hull_vertices(shape)) s = std::max(s, v.norm());
      return s;
    }
    default:
      return 1.0;
  }
}

#define WEDGE_INSTANTIATE(N)                                                                                   \
  template Vec<N> local_support<N>(const Shape<N>&, const Vec<N>&);                                            \
  template void local_support_set<N>(const Shape<N>&, const Vec<N>&, double, std::vector<SupportPoint<N>>&);   \
  template bool local_contains<N>(const Shape<N>&, const Vec<N>&, double);                                     \
  template double shape_scale<N>(const Shape<N>&);                                                             \
  template const std::vector<ProductFactor>& product_factors<N>(const Shape<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
