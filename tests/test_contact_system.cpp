// The solver's per-point algebra (contact/contact_system.hpp), against the matrices it replaces: the
// angular change I^-1 (r ^ j) and K's angular part [r]_*^T I^-1 [r]_*, formed from the paper's
// explicit lever-arm matrix [r]_* (eq. 3) and a full inverse inertia, for general and isotropic bodies;
// how the soft step packs its constraints into lanes, and the lanes' arithmetic.
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

// A contact state whose constraints have the given point counts and bodies, and colour groups
// colour_start (the last group uncoloured); every point's fields are distinct numbers.
contact::ContactState<2> constraints_with(const std::vector<int>& counts, const std::vector<std::pair<int, int>>& bodies,
                                          std::vector<int> colour_start, int body_count) {
  contact::ContactState<2> s;
  s.solver_bodies.resize(body_count);
  for (int i = 0; i < body_count; ++i) {
    s.solver_bodies[i].inv_mass = 1.0 + i;
    s.solver_bodies[i].isotropic = true;
    s.solver_bodies[i].iso_inv_inertia = 2.0 + i;
  }
  int first = 0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    contact::Constraint<2> c;
    c.first = first;
    c.count = counts[k];
    c.a = bodies[k].first;
    c.b = bodies[k].second;
    c.normal = Vec<2>(0.6, 0.8);
    s.constraints.push_back(c);
    for (int j = 0; j < c.count; ++j) {
      contact::PointConstraint<2> p;
      p.jn_a.setZero();
      p.jn_b.setZero();
      p.dn_a.setZero();
      p.dn_b.setZero();
      const double id = 100.0 * double(k) + j + 1.0;
      p.normal_mass = id;
      p.normal_impulse = id + 0.25;
      p.separation = -id;
      p.jn_a[0] = id + 0.5;
      p.tangent_impulse = Vec<2>(id, -id);
      p.tangent_mass << id, 1.0, 2.0, id;
      p.rb = Vec<2>(-id, 3.0);
      s.points.push_back(p);
    }
    first += c.count;
  }
  s.colour_start = std::move(colour_start);
  return s;
}

}  // namespace

// The lanes hold the constraints as they are: each constraint in exactly one lane, its k-th point in
// slot k of that lane, zero past its last point; a colour's lanes hold that colour's constraints only,
// most points first; the uncoloured group (whose constraints may share a moving body) one per wide
// constraint, in order. Bodies that do not move are never written back.
TEST_CASE("the soft step packs each colour's constraints into lanes, point for point", "[contact]") {
  constexpr int L = contact::kLanes<2>;
  // Colour 0: constraints 0..L+1 (more than one wide constraint's worth, counts 1 and 2 mixed),
  // colour 1: one constraint, the uncoloured group: two constraints sharing body 1. Body 0 is frozen
  // (the ground), body 1 is not isotropic.
  std::vector<int> counts;
  std::vector<std::pair<int, int>> bodies;
  for (int k = 0; k < L + 2; ++k) {
    counts.push_back(k % 3 == 0 ? 1 : 2);
    bodies.push_back({0, 2 + k});
  }
  const int colour0 = L + 2;
  counts.push_back(2);
  bodies.push_back({1, 2});
  counts.insert(counts.end(), {1, 2});
  bodies.insert(bodies.end(), {{1, 3}, {1, 4}});
  contact::ContactState<2> s = constraints_with(counts, bodies, {0, colour0, colour0 + 1, colour0 + 3}, L + 4);
  s.solver_bodies[0].frozen = true;
  s.solver_bodies[0].inv_mass = 0.0;
  s.solver_bodies[0].iso_inv_inertia = 0.0;
  s.solver_bodies[1].isotropic = false;
  s.solver_bodies[1].inv_inertia(0, 0) = 7.0;
  contact::pack_wide(s);

  // Colour 0 takes two wide constraints, colour 1 one, the uncoloured group two.
  REQUIRE(s.wide_start == std::vector<int>{0, 2, 3, 5});
  std::vector<int> seen(s.constraints.size(), 0);
  int slots = 0;
  for (int g = 0; g + 1 < int(s.wide_start.size()); ++g) {
    int last_count = 1 << 30;
    for (int w = s.wide_start[g]; w < s.wide_start[g + 1]; ++w) {
      const contact::WideConstraint<2>& wc = s.wide[w];
      CHECK(wc.first == slots);
      slots += wc.count;
      int most = 0, used = 0;
      for (int l = 0; l < L; ++l) {
        const int k = wc.constraint[l];
        if (k < 0) {
          CHECK(wc.a[l] == -1);
          CHECK(wc.b[l] == -1);
          CHECK((wc.move_a >> l & 1u) == 0u);
          for (int j = 0; j < wc.count; ++j) CHECK(s.wide_points[wc.first + j].normal_mass[l] == 0.0);
          continue;
        }
        ++used;
        ++seen[k];
        CHECK(k >= s.colour_start[g]);
        CHECK(k < s.colour_start[g + 1]);
        const contact::Constraint<2>& c = s.constraints[k];
        if (g + 2 < int(s.wide_start.size())) CHECK(c.count <= last_count);  // most points first in a colour
        last_count = c.count;
        most = std::max(most, c.count);
        CHECK(wc.a[l] == c.a);
        CHECK(wc.b[l] == c.b);
        CHECK(bool(wc.move_a >> l & 1u) == !s.solver_bodies[c.a].frozen);
        CHECK(bool(wc.move_b >> l & 1u) == !s.solver_bodies[c.b].frozen);
        CHECK(wc.normal[1][l] == 0.8);
        CHECK(wc.inv_mass_a[l] == s.solver_bodies[c.a].inv_mass);
        CHECK(wc.iso_b[l] == s.solver_bodies[c.b].iso_inv_inertia);
        for (int j = 0; j < wc.count; ++j) {
          const contact::WidePoint<2>& q = s.wide_points[wc.first + j];
          if (j >= c.count) {
            CHECK(q.normal_mass[l] == 0.0);
            CHECK(q.friction[l] == 0.0);
            continue;
          }
          const contact::PointConstraint<2>& p = s.points[c.first + j];
          CHECK(q.normal_mass[l] == p.normal_mass);
          CHECK(q.normal_impulse[l] == p.normal_impulse);
          CHECK(q.separation[l] == p.separation);
          CHECK(q.jn_a[0][l] == p.jn_a[0]);
          CHECK(q.tangent_impulse[1][l] == p.tangent_impulse[1]);
          CHECK(q.tangent_mass[2][l] == p.tangent_mass(0, 1));  // column-major
          CHECK(q.rb[0][l] == p.rb[0]);
        }
      }
      CHECK(wc.count == most);
      // Only the uncoloured group goes one to a wide constraint.
      CHECK(used == (g + 2 == int(s.wide_start.size()) ? 1 : std::min(L, s.colour_start[g + 1] - s.colour_start[g] - (w - s.wide_start[g]) * L)));
      // A moving body that is not isotropic brings its inverse inertia matrix along.
      const bool general = (wc.a[0] == 1);
      CHECK((wc.inertia >= 0) == general);
      if (general) CHECK(s.wide_inertia[wc.inertia].a[0][0] == 7.0);
    }
  }
  CHECK(s.wide_points.size() == std::size_t(slots));
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  // The uncoloured group keeps its order.
  CHECK(s.wide[3].constraint[0] == colour0 + 1);
  CHECK(s.wide[4].constraint[0] == colour0 + 2);
}

TEST_CASE("wide values compute lane by lane", "[contact]") {
  using W = contact::Wide<3>;
  constexpr int L = contact::kLanes<3>;
  const W a = contact::make_wide<W>([](int l) { return double(l) - 1.5; });
  const W b = contact::make_wide<W>([](int l) { return 0.5 * l; });
  const W sum = a + b, scaled = 2.0 * a - b * 3.0;
  const contact::WideMask<3> negative = a < 0.0;
  const W chosen = contact::select(negative, b, a);
  for (int l = 0; l < L; ++l) {
    CHECK(sum[l] == (double(l) - 1.5) + 0.5 * l);
    CHECK(scaled[l] == 2.0 * (double(l) - 1.5) - 0.5 * l * 3.0);
    CHECK(negative[l] == (l < 2));
    CHECK(chosen[l] == (l < 2 ? 0.5 * l : double(l) - 1.5));
  }
  CHECK(contact::any(negative));
  CHECK_FALSE(contact::any(a > 100.0));
  W c = a;
  c.set(L - 1, -7.0);
  CHECK(c[L - 1] == -7.0);
  CHECK(c[0] == a[0]);
}
