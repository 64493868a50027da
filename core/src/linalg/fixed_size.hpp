// Internal: Eigen's LU-based kernels for the fixed sizes the engine uses (N x N for N = 2..6, and k x k
// for the bivector counts k = 1, 3, 6, 10, 15), compiled once in fixed_size.cpp instead of in every file
// that needs them. Eigen inverts and takes determinants of matrices up to 4 x 4 in closed form, inline
// and cheap to compile; beyond that it goes through a PartialPivLU whose instantiation took several
// seconds of compile time per size in each file (a third of contact/grab.cpp's). Calling the same Eigen
// code compiled elsewhere gives the same bits.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace wedge::linalg {

template <int R>
using Square = Eigen::Matrix<double, R, R>;
template <int R>
using Column = Eigen::Matrix<double, R, 1>;

// The out-of-line kernels (defined for R = 5, 6, 10, 15; solve_lu for 1, 3, 6, 10, 15 too).
template <int R>
Square<R> inverse_lu(const Square<R>& m);
template <int R>
double determinant_lu(const Square<R>& m);
template <int R>
Column<R> solve_lu(const Square<R>& a, const Column<R>& b);

// m^-1, as Eigen's m.inverse(): closed form up to 4 x 4, partial-pivoting LU beyond.
template <int R>
inline Square<R> inverse(const Square<R>& m) {
  if constexpr (R <= 4)
    return m.inverse();
  else
    return inverse_lu<R>(m);
}

// det(m), as Eigen's m.determinant(): closed form up to 4 x 4, partial-pivoting LU beyond.
template <int R>
inline double determinant(const Square<R>& m) {
  if constexpr (R <= 4)
    return m.determinant();
  else
    return determinant_lu<R>(m);
}

// a^-1 b by partial-pivoting LU (a.partialPivLu().solve(b)), at every size.
template <int R>
inline Column<R> solve(const Square<R>& a, const Column<R>& b) {
  return solve_lu<R>(a, b);
}

// A partial-pivoting LU factorisation of a, kept for several right-hand sides (Eigen's PartialPivLU; the
// sizes of WEDGE_LINALG_FIXED_SOLVE).
template <int R>
class LuFactors {
 public:
  explicit LuFactors(const Square<R>& a);
  Column<R> solve(const Column<R>& b) const;

 private:
  Eigen::PartialPivLU<Square<R>> lu_;
};

#define WEDGE_LINALG_FIXED_LARGE(X) X(5) X(6) X(10) X(15)
#define WEDGE_LINALG_FIXED_SOLVE(X) X(1) X(3) X(5) X(6) X(10) X(15)
#define WEDGE_LINALG_DECLARE_LARGE(R)                            \
  extern template Square<R> inverse_lu<R>(const Square<R>&); \
  extern template double determinant_lu<R>(const Square<R>&);
#define WEDGE_LINALG_DECLARE_SOLVE(R)                                            \
  extern template Column<R> solve_lu<R>(const Square<R>&, const Column<R>&); \
  extern template class LuFactors<R>;
WEDGE_LINALG_FIXED_LARGE(WEDGE_LINALG_DECLARE_LARGE)
WEDGE_LINALG_FIXED_SOLVE(WEDGE_LINALG_DECLARE_SOLVE)
#undef WEDGE_LINALG_DECLARE_LARGE
#undef WEDGE_LINALG_DECLARE_SOLVE

}  // namespace wedge::linalg
