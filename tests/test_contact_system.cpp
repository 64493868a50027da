// The solver's per-point algebra (contact/contact_system.hpp), against the matrices it replaces: the
// angular change I^-1 (r ^ j) and K's angular part [r]_*^T I^-1 [r]_*, formed from the paper's
// explicit lever-arm matrix [r]_* (eq. 3) and a full inverse inertia, for general and isotropic bodies.
#include <catch2/catch.hpp>
#include <random>

#include "contact/contact_system.hpp"

using namespace wedge;

namespace {

template <int N>
Vec<N> random_vector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = u(rng);
  return v;
}

// A symmetric positive definite k x k inverse inertia: A A^T + 0.1.
template <int N>
BivMat<N> random_inverse_inertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BivMat<N> a;
  for (int i = 0; i < kBiv<N>; ++i)
    for (int j = 0; j < kBiv<N>; ++j) a(i, j) = u(rng);
  return a * a.transpose() + 0.1 * BivMat<N>::Identity();
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("a point's angular change and K term equal the lever-arm matrix products (2D-6D)",
                       "[contact][solver_algebra]", ((int N), N), 2, 3, 4, 5, 6) {
  std::mt19937 rng(15 + N);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<N> r = random_vector<N>(rng), j = random_vector<N>(rng);
    const WedgeMat<N> jr = wedge_matrix<N>(r);
    contact::SolverBody<N> general;
    general.inv_inertia = random_inverse_inertia<N>(rng);
    contact::SolverBody<N> isotropic;
    isotropic.isotropic = true;
    isotropic.iso_inv_inertia = 0.25 + 0.01 * trial;
    isotropic.inv_inertia = isotropic.iso_inv_inertia * BivMat<N>::Identity();
    for (const contact::SolverBody<N>* b : {&general, &isotropic}) {
      // Sums of a few products of numbers below 10: agreement to 1e-12 is round-off; a wrong sign or
      // index is off by order 1.
      const Eigen::Matrix<double, kBiv<N>, 1> expected = b->inv_inertia * (jr * j);
      REQUIRE((contact::angular_change(*b, r, j) - expected).norm() <= 1e-12 * (1.0 + expected.norm()));
      const Mat<N> k = jr.transpose() * b->inv_inertia * jr;
      REQUIRE((contact::angular_mass_term(*b, r) - k).norm() <= 1e-12 * (1.0 + k.norm()));
    }
  }
}
