// Internal: whether an inertia (or its inverse) is the same about every plane, exactly. Cubes, balls and
// their n-dimensional kin have one; the step then skips their gyroscopic solve (world.cpp) and the
// contact passes scale by a number instead of multiplying by the matrix (contact/pairs.cpp).
#pragma once

namespace wedge::linalg {

// m is m(0, 0) times the identity, to the last bit.
template <class M>
bool is_isotropic(const M& m) {
  return m == M(m(0, 0) * M::Identity());
}

}  // namespace wedge::linalg
