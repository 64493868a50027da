#include "linalg/fixed_size.hpp"

namespace wedge::linalg {

template <int R>
Square<R> inverse_lu(const Square<R>& m) {
  return m.inverse();
}

template <int R>
double determinant_lu(const Square<R>& m) {
  return m.determinant();
}

template <int R>
Column<R> solve_lu(const Square<R>& a, const Column<R>& b) {
  return a.partialPivLu().solve(b);
}

template <int R>
LuFactors<R>::LuFactors(const Square<R>& a) : lu_(a) {}
template <int R>
Column<R> LuFactors<R>::solve(const Column<R>& b) const {
  return lu_.solve(b);
}

#define WEDGE_LINALG_DEFINE_LARGE(R)                      \
  template Square<R> inverse_lu<R>(const Square<R>&); \
  template double determinant_lu<R>(const Square<R>&);
#define WEDGE_LINALG_DEFINE_SOLVE(R)                                      \
  template Column<R> solve_lu<R>(const Square<R>&, const Column<R>&); \
  template class LuFactors<R>;
WEDGE_LINALG_FIXED_LARGE(WEDGE_LINALG_DEFINE_LARGE)
WEDGE_LINALG_FIXED_SOLVE(WEDGE_LINALG_DEFINE_SOLVE)

}  // namespace wedge::linalg
