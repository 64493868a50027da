// The six convex regular 4-polytopes as ready-made shapes, centred at the origin, by circumradius.
//
//   enum        names accepted           vertices  edges  cells                 Schläfli
//   Cell5       "5-cell"                        5     10      5 tetrahedra      {3,3,3}
//   Cell8       "8-cell", "tesseract"          16     32      8 cubes           {4,3,3}
//   Cell16      "16-cell"                       8     24     16 tetrahedra      {3,3,4}
//   Cell24      "24-cell"                      24     96     24 octahedra       {3,4,3}
//   Cell120     "120-cell"                    600   1200    120 dodecahedra     {5,3,3}
//   Cell600     "600-cell"                    120    720    600 tetrahedra      {3,3,5}
//
// The enumerators are named by cell count (Cell8 is the tesseract). Vertex coordinates are the standard
// ones (Coxeter, Regular Polytopes, 1973, table I and section 8.7), scaled to the circumradius.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wedge/ga/types.hpp"
#include "wedge/shape.hpp"

namespace wedge {

enum class RegularPolytope4 { Cell5, Cell8, Cell16, Cell24, Cell120, Cell600 };

inline constexpr std::array<RegularPolytope4, 6> kRegularPolytopes4 = {
    RegularPolytope4::Cell5,  RegularPolytope4::Cell8,   RegularPolytope4::Cell16,
    RegularPolytope4::Cell24, RegularPolytope4::Cell120, RegularPolytope4::Cell600};

// The canonical name: "5-cell", "tesseract", "16-cell", "24-cell", "120-cell", "600-cell".
std::string_view regular_polytope_name(RegularPolytope4 which);
// Accepts the canonical names and "8-cell" for the tesseract; nullopt for anything else.
std::optional<RegularPolytope4> parse_regular_polytope(std::string_view name);
// The accepted names, comma separated, for error messages.
std::string regular_polytope_names();

// The vertices on the 3-sphere of the given radius (> 0 and finite, else wedge::Error), in a fixed
// order. Every vertex is extreme.
std::vector<Vec<4>> regular_polytope_vertices(RegularPolytope4 which, double circumradius);

// Shape<4>::polytope of those vertices.
Shape<4> regular_polytope_shape(RegularPolytope4 which, double circumradius);

}  // namespace wedge
