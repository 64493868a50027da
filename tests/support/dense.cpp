#include "dense.hpp"

#include <Eigen/LU>
#include <Eigen/QR>

namespace dense {

double determinant(const Eigen::MatrixXd& a) { return Eigen::PartialPivLU<Eigen::MatrixXd>(a).determinant(); }

Eigen::MatrixXd haar_rotation(const Eigen::MatrixXd& gaussian) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(gaussian);
  Eigen::MatrixXd q = qr.householderQ();
  const Eigen::MatrixXd r = qr.matrixQR().triangularView<Eigen::Upper>();
  for (int j = 0; j < int(q.cols()); ++j)
    if (r(j, j) < 0.0) q.col(j) = -q.col(j);
  if (determinant(q) < 0.0) q.col(0) = -q.col(0);
  return q;
}

bool kernel_vector(const Eigen::MatrixXd& a, Eigen::VectorXd& out) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (lu.rank() < a.cols() - 1) return false;
  out = lu.kernel().col(0).normalized();
  return true;
}

bool solve_invertible(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible()) return false;
  x = lu.solve(b);
  return true;
}

Eigen::VectorXd least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return a.colPivHouseholderQr().solve(b);
}

}  // namespace dense
