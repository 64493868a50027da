// Internal: whether an inertia (or its inverse) is the same about every plane, exactly. Cubes, balls and
// their n-dimensional kin have one; the step then skips their gyroscopic solve (world.cpp) and the
// contact passes scale by a number instead of multiplying by the matrix (contact/build.cpp).
#pragma once

namespace wedge::linalg {

// m is m(0, 0) times the identity, to the last bit (an anisotropic inertia usually fails at (1, 1)).
template <class M>
bool is_isotropic(const M& m) {
  const double d = m(0, 0);
  for (int j = 0; j < m.cols(); ++j)
    for (int i = 0; i < m.rows(); ++i)
      if (m(i, j) != (i == j ? d : 0.0)) return false;
  return true;
}

}  // namespace wedge::linalg
