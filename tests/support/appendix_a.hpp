// The paper's appendix A matrices, transcribed literally ("w^2 + x^2", "-wx" as printed), for
// r = (x, y[, z, w]): [r]_* (k x n) and Delta I = [r]_* [r]_*^T (k x k), rows and columns in the paper's
// lexicographic bivector order e_xy, e_xz, (e_xw,) e_yz, (e_yw, e_zw). Used by test_appendix_a.cpp and
// test_mass.cpp as the oracle.
#pragma once

#include "wedge/ga/types.hpp"

namespace paper {

inline wedge::WedgeMat<2> wedge_matrix(const wedge::Vec<2>& r) {
  const double x = r[0], y = r[1];
  wedge::WedgeMat<2> m;
  m << -y, x;
  return m;
}
inline wedge::BivMat<2> delta_i(const wedge::Vec<2>& r) {
  const double x = r[0], y = r[1];
  wedge::BivMat<2> m;
  m << x * x + y * y;
  return m;
}

inline wedge::WedgeMat<3> wedge_matrix(const wedge::Vec<3>& r) {
  const double x = r[0], y = r[1], z = r[2];
  wedge::WedgeMat<3> m;
  m << -y, x, 0,  //
      -z, 0, x,   //
      0, -z, y;
  return m;
}
inline wedge::BivMat<3> delta_i(const wedge::Vec<3>& r) {
  const double x = r[0], y = r[1], z = r[2];
  wedge::BivMat<3> m;
  m << x * x + y * y, y * z, -x * z,  //
      y * z, x * x + z * z, x * y,    //
      -x * z, x * y, y * y + z * z;
  return m;
}

inline wedge::WedgeMat<4> wedge_matrix(const wedge::Vec<4>& r) {
  const double x = r[0], y = r[1], z = r[2], w = r[3];
  wedge::WedgeMat<4> m;
  m << -y, x, 0, 0,  //
      -z, 0, x, 0,   //
      -w, 0, 0, x,   //
      0, -z, y, 0,   //
      0, -w, 0, y,   //
      0, 0, -w, z;
  return m;
}
inline wedge::BivMat<4> delta_i(const wedge::Vec<4>& r) {
  const double x = r[0], y = r[1], z = r[2], w = r[3];
  wedge::BivMat<4> m;
  m << x * x + y * y, y * z, y * w, -x * z, -x * w, 0,  //
      y * z, x * x + z * z, z * w, x * y, 0, -x * w,    //
      y * w, z * w, w * w + x * x, 0, x * y, x * z,     //
      -x * z, x * y, 0, y * y + z * z, z * w, -y * w,   //
      -x * w, 0, x * y, z * w, w * w + y * y, y * z,    //
      0, -w * x, x * z, -y * w, y * z, w * w + z * z;
  return m;
}

}  // namespace paper
