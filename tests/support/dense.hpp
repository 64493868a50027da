// Eigen's costly decompositions for the tests, compiled once for dynamic sizes (dense.cpp) instead of
// once per dimension in every test file that needs them. A fixed-size HouseholderQR or FullPivLU for
// each of N = 2..6 cost 40-100 s of compile time per file; the tests call them on a few thousand small
// matrices, where a heap allocation does not matter. (core/src/linalg/decompositions.hpp does the same
// for the library.)
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // MatrixBase::determinant (its closed forms up to 4 x 4)

namespace dense {

// det a, by partial-pivot LU.
double determinant(const Eigen::MatrixXd& a);

// The Q factor of the QR decomposition of a square Gaussian matrix, with R's diagonal made positive and
// then det Q = +1 (column 0 flipped if needed): a uniformly random rotation (Haar measure on SO(n)).
Eigen::MatrixXd haar_rotation(const Eigen::MatrixXd& gaussian);

// A unit vector spanning the kernel of an (n - 1) x n matrix of rank n - 1, by full-pivot LU. False, with
// `out` untouched, when the rank is lower (the kernel is not a line).
bool kernel_vector(const Eigen::MatrixXd& a, Eigen::VectorXd& out);

// x with a x = b, by full-pivot LU. False, with `x` untouched, when a is singular.
bool solve_invertible(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);

// The least-squares solution of a x = b, by column-pivoting QR.
Eigen::VectorXd least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

}  // namespace dense

// det m for any fixed-size square matrix or expression: Eigen's closed forms up to 4 x 4 (cheap to
// compile), the compiled-once LU above that.
template <class Derived>
double det(const Eigen::MatrixBase<Derived>& m) {
  constexpr int n = Derived::RowsAtCompileTime;
  static_assert(n == Derived::ColsAtCompileTime && n > 0, "det: a fixed-size square matrix");
  if constexpr (n <= 4)
    return m.determinant();
  else
    return dense::determinant(m);
}
