#include "wedge/regular_polytopes.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "wedge/error.hpp"

namespace wedge {
namespace {

using Point = std::array<double, 4>;

// Parity of a permutation of 0..3 by counting inversions.
bool is_even(const std::array<int, 4>& p) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[std::size_t(i)] > p[std::size_t(j)] ? 1 : 0;
  return inversions % 2 == 0;
}

// All points obtained from `base` by a permutation of its coordinates (every one, or only the even
// ones) and any choice of signs; duplicates (from zeros and repeated entries) are dropped. Only
// permutations and sign changes are applied, so equal points compare exactly equal.
void add_orbit(std::set<Point>& out, const Point& base, bool even_only) {
  std::array<int, 4> perm = {0, 1, 2, 3};
  do {
    if (even_only && !is_even(perm)) continue;
    for (int signs = 0; signs < 16; ++signs) {
      Point p;
      for (int i = 0; i < 4; ++i) {
        const double v = base[std::size_t(perm[std::size_t(i)])];
        p[std::size_t(i)] = (signs >> i) & 1 ? -v : v;
      }
      for (double& v : p) v = v == 0.0 ? 0.0 : v;  // -0 -> +0, so zeros deduplicate
      out.insert(p);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
}

struct Unscaled {
  std::set<Point> points;
  double circumradius;
};

Unscaled unscaled_vertices(RegularPolytope4 which) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0, s5 = std::sqrt(5.0);
  Unscaled u;
  switch (which) {
    case RegularPolytope4::Cell5: {
      // A regular tetrahedron (alternate vertices of the cube (+-1)^3) at w = -1/sqrt5 and the apex
      // (0, 0, 0, 4/sqrt5): every vertex has norm 4/sqrt5, every edge 2 sqrt2.
      const double w = -1.0 / s5;
      u.points = {{1, 1, 1, w}, {1, -1, -1, w}, {-1, 1, -1, w}, {-1, -1, 1, w}, {0, 0, 0, 4.0 / s5}};
      u.circumradius = 4.0 / s5;
      break;
    }
    case RegularPolytope4::Cell8:  // (+-1, +-1, +-1, +-1): circumradius 2, edge 2
      add_orbit(u.points, {1, 1, 1, 1}, false);
      u.circumradius = 2.0;
      break;
    case RegularPolytope4::Cell16:  // permutations of (+-1, 0, 0, 0): circumradius 1, edge sqrt2
      add_orbit(u.points, {1, 0, 0, 0}, false);
      u.circumradius = 1.0;
      break;
    case RegularPolytope4::Cell24:  // permutations of (+-1, +-1, 0, 0): circumradius sqrt2, edge sqrt2
      add_orbit(u.points, {1, 1, 0, 0}, false);
      u.circumradius = std::sqrt(2.0);
      break;
    case RegularPolytope4::Cell600:
      // Coxeter 8.7: permutations of (+-2, 0, 0, 0), (+-1, +-1, +-1, +-1) and the even permutations of
      // (+-phi, +-1, +-1/phi, 0): 8 + 16 + 96 = 120 points of norm 2, edge 2/phi.
      add_orbit(u.points, {2, 0, 0, 0}, false);
      add_orbit(u.points, {1, 1, 1, 1}, false);
      add_orbit(u.points, {phi, 1, 1 / phi, 0}, true);
      u.circumradius = 2.0;
      break;
    case RegularPolytope4::Cell120:
      // Coxeter 8.7 (the dual of the 600-cell): 24 + 64 + 64 + 64 + 96 + 96 + 192 = 600 points of norm
      // sqrt8, edge 2/phi^2 = 3 - sqrt5.
      add_orbit(u.points, {2, 2, 0, 0}, false);
      add_orbit(u.points, {1, 1, 1, s5}, false);
      add_orbit(u.points, {1 / (phi * phi), phi, phi, phi}, false);
      add_orbit(u.points, {1 / phi, 1 / phi, 1 / phi, phi * phi}, false);
      add_orbit(u.points, {0, 1 / (phi * phi), 1, phi * phi}, true);
      add_orbit(u.points, {0, 1 / phi, phi, s5}, true);
      add_orbit(u.points, {1 / phi, 1, phi, 2}, true);
      u.circumradius = std::sqrt(8.0);
      break;
  }
  return u;
}

}  // namespace

std::string_view regular_polytope_name(RegularPolytope4 which) {
  switch (which) {
    case RegularPolytope4::Cell5: return "5-cell";
    case RegularPolytope4::Cell8: return "tesseract";
    case RegularPolytope4::Cell16: return "16-cell";
    case RegularPolytope4::Cell24: return "24-cell";
    case RegularPolytope4::Cell120: return "120-cell";
    case RegularPolytope4::Cell600: return "600-cell";
  }
  return "?";
}

std::optional<RegularPolytope4> parse_regular_polytope(std::string_view name) {
  if (name == "8-cell") return RegularPolytope4::Cell8;
  for (RegularPolytope4 p : kRegularPolytopes4)
    if (name == regular_polytope_name(p)) return p;
  return std::nullopt;
}

std::string regular_polytope_names() {
  std::string s;
  for (RegularPolytope4 p : kRegularPolytopes4) {
    if (!s.empty()) s += ", ";
    s += regular_polytope_name(p);
    if (p == RegularPolytope4::Cell8) s += " (or 8-cell)";
  }
  return s;
}

std::vector<Vec<4>> regular_polytope_vertices(RegularPolytope4 which, double circumradius) {
  if (!(std::isfinite(circumradius) && circumradius > 0.0)) {
    std::ostringstream s;
    s << "the circumradius of a " << regular_polytope_name(which) << " must be positive and finite (got "
      << circumradius << ")";
    throw Error(s.str());
  }
  const Unscaled u = unscaled_vertices(which);
  const double scale = circumradius / u.circumradius;
  std::vector<Vec<4>> out;
  out.reserve(u.points.size());
  for (const Point& p : u.points) out.push_back(Vec<4>(p[0], p[1], p[2], p[3]) * scale);
  return out;
}

Shape<4> regular_polytope_shape(RegularPolytope4 which, double circumradius) {
  return Shape<4>::polytope(regular_polytope_vertices(which, circumradius));
}

}  // namespace wedge
