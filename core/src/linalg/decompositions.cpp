#include "linalg/decompositions.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

namespace wedge::linalg {

Eigen::VectorXd singular_values(const Eigen::MatrixXd& a) { return Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues(); }

std::vector<Eigen::VectorXd> column_space_basis(const Eigen::MatrixXd& a, double tolerance) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU);
  std::vector<Eigen::VectorXd> basis;
  for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i)
    if (svd.singularValues()[i] > tolerance) basis.push_back(svd.matrixU().col(i));
  return basis;
}

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& s) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s, Eigen::EigenvaluesOnly).eigenvalues();
}

bool symmetric_eigen(const SmallMatrix& s, SmallVector& values, SmallMatrix& vectors) {
  const Eigen::SelfAdjointEigenSolver<SmallMatrix> es(s);
  if (es.info() != Eigen::Success) return false;
  values = es.eigenvalues();
  vectors = es.eigenvectors();
  return true;
}

SmallVector solve_rank_revealing(const SmallMatrix& a, const SmallVector& b, double threshold) {
  Eigen::ColPivHouseholderQR<SmallMatrix> qr(a);
  qr.setThreshold(threshold);
  return qr.solve(b);
}

}  // namespace wedge::linalg
