// Internal: Eigen's costly decompositions, compiled once for dynamic sizes instead of once per dimension
// and per file. They serve cold paths (hulls, face lattices, mass properties, body checks), where a heap
// allocation does not matter and the compile time did: a JacobiSVD or a SelfAdjointEigenSolver for each
// of n = 2..6 cost about 20 s of compile time per file.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace wedge::linalg {

// The singular values of a, largest first.
Eigen::VectorXd singular_values(const Eigen::MatrixXd& a);

// The left singular vectors of a whose singular values exceed `tolerance`: an orthonormal basis of the
// column space of a, with directions below the tolerance dropped.
std::vector<Eigen::VectorXd> column_space_basis(const Eigen::MatrixXd& a, double tolerance);

// The eigenvalues of the symmetric matrix s, ascending (its lower triangle is read).
Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& s);

// Matrices of at most 6 x 6 (the largest N) with their storage inline: no heap allocation, for the code
// that runs in every step (the narrow phase, the rotor exponential and logarithm).
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// The eigen-decomposition of the symmetric matrix s (at most 6 x 6: the world's N x N matrices, in the
// step's rotor exponential and logarithm, so without heap allocation): eigenvalues ascending,
// eigenvectors as columns. False when the iteration did not converge.
bool symmetric_eigen(const SmallMatrix& s, SmallVector& values, SmallMatrix& vectors);

// The least-squares solution of a x = b by column-pivoting QR, with the directions whose pivots fall below
// `threshold` (relative to the largest) dropped: their coefficients are 0 (rank-revealing).
SmallVector solve_rank_revealing(const SmallMatrix& a, const SmallVector& b, double threshold);

}  // namespace wedge::linalg
