// The solver's per-point algebra (contact/contact_system.hpp), against the matrices it replaces: the
// angular change I^-1 (r ^ j) and K's angular part [r]_*^T I^-1 [r]_*, formed from the paper's
// explicit lever-arm matrix [r]_* (eq. 3) and a full inverse inertia, for general and isotropic bodies;
// and the order in which the passes visit the constraints and their points.
#include <catch2/catch.hpp>
#include <random>
#include <string>

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

namespace {

// A contact state with constraints of the given point counts, points laid out in order.
contact::ContactState<2> constraints_with(const std::vector<int>& counts, std::vector<int> colour_start) {
  contact::ContactState<2> s;
  int first = 0;
  for (const int count : counts) {
    contact::Constraint<2> c;
    c.first = first;
    c.count = count;
    s.constraints.push_back(c);
    first += count;
  }
  s.colour_start = std::move(colour_start);
  return s;
}

// The visits of for_each_constraint_in_pairs, as "1:k" (one constraint alone) and "2:k,l" (two in turn).
std::string visits(contact::ContactState<2>& s) {
  std::string out;
  const auto index = [&](const contact::Constraint<2>& c) { return std::to_string(&c - s.constraints.data()); };
  contact::for_each_constraint_in_pairs(
      s, [&](const contact::Constraint<2>& c) { out += "1:" + index(c) + " "; },
      [&](const contact::Constraint<2>& c, const contact::Constraint<2>& d) {
        out += "2:" + index(c) + "," + index(d) + " ";
      });
  return out;
}

}  // namespace

// Two constraints of a colour share no moving body, so taking them point by point in turn gives the bits
// of taking them one after the other; constraints of the uncoloured group (which may share bodies) and
// the paper's solver's (in pair order) must go one at a time, each exactly once, in solver order.
TEST_CASE("the passes take two constraints of a colour in turn and every other constraint alone, in order",
          "[contact]") {
  // Colour 0: constraints 0-4 (an odd count: the last goes alone), colour 1: 5, then the uncoloured
  // group 6-7, then the end.
  contact::ContactState<2> coloured = constraints_with({2, 1, 2, 2, 3, 1, 2, 2}, {0, 5, 6, 8});
  CHECK(visits(coloured) == "2:0,1 2:2,3 1:4 1:5 1:6 1:7 ");
  // An empty colour is skipped.
  contact::ContactState<2> empty_colour = constraints_with({2, 2, 2}, {0, 2, 2, 3});
  CHECK(visits(empty_colour) == "2:0,1 1:2 ");
  // The paper's solver: no colours, all alone in pair order.
  contact::ContactState<2> paper = constraints_with({2, 2, 2}, {});
  CHECK(visits(paper) == "1:0 1:1 1:2 ");

  // points_in_turn: every point of both once, alternating while both have points.
  std::string order;
  contact::points_in_turn(coloured.constraints[4], coloured.constraints[1],
                          [&](const contact::Constraint<2>& c, int k) {
                            order += std::to_string(&c - coloured.constraints.data()) + "." + std::to_string(k) + " ";
                          });
  CHECK(order == "4.0 1.0 4.1 4.2 ");
}
