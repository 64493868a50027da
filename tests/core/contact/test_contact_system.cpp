// The solver's per-point algebra (contact/contact_system.hpp), against the matrices it replaces: the
// angular change I^-1 (r ^ j) and K's angular part [r]_*^T I^-1 [r]_*, formed from the paper's
// explicit lever-arm matrix [r]_* (eq. 3) and a full inverse inertia, for general and isotropic bodies;
// how the soft step packs its constraints into lanes, and the lanes' arithmetic; its warm start body by
// body against every point's impulse applied point by point.
#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <string>

#include "contact_bodies.hpp"
#include "contact/contact_system.hpp"
#include "contact/impulses.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/mass.hpp"

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
    contact::BodyMass<N> general;
    general.inv_inertia = random_inverse_inertia<N>(rng);
    contact::BodyMass<N> isotropic;
    isotropic.isotropic = true;
    isotropic.iso_inv_inertia = 0.25 + 0.01 * trial;
    isotropic.inv_inertia = isotropic.iso_inv_inertia * BivMat<N>::Identity();
    for (const contact::BodyMass<N>* b : {&general, &isotropic}) {
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
contact::ContactState<2> constraints_with(const std::vector<int>& counts,
                                          const std::vector<std::pair<int, int>>& bodies,
                                          std::vector<int> colour_start, int body_count) {
  contact::ContactState<2> s;
  s.solver_bodies.resize(body_count);
  s.masses.resize(body_count);
  for (int i = 0; i < body_count; ++i) {
    s.masses[i].inv_mass = 1.0 + i;
    s.masses[i].isotropic = true;
    s.masses[i].iso_inv_inertia = 2.0 + i;
  }
  int first = 0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    contact::Constraint<2> c;
    c.first = first;
    c.count = counts[k];
    c.a = bodies[k].first;
    c.b = bodies[k].second;
    c.normal = Vec<2>(0.6, 0.8);
    s.graph.constraints.push_back(c);
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
      s.paper.points.push_back(p);
    }
    first += c.count;
  }
  s.graph.colour_start = std::move(colour_start);
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
  s.masses[0].inv_mass = 0.0;
  s.masses[0].iso_inv_inertia = 0.0;
  s.masses[1].isotropic = false;
  s.masses[1].inv_inertia(0, 0) = 7.0;
  contact::pack_wide(s);

  // Colour 0 takes two wide constraints, colour 1 one, the uncoloured group two.
  REQUIRE(s.soft.wide_start == std::vector<int>{0, 2, 3, 5});
  std::vector<int> seen(s.graph.constraints.size(), 0);
  int slots = 0;
  for (int g = 0; g + 1 < int(s.soft.wide_start.size()); ++g) {
    int last_count = 1 << 30;
    for (int w = s.soft.wide_start[g]; w < s.soft.wide_start[g + 1]; ++w) {
      const contact::WideConstraint<2>& wc = s.soft.wide[w];
      CHECK(wc.first == slots);
      slots += wc.count;
      int most = 0, used = 0;
      for (int l = 0; l < L; ++l) {
        const int k = wc.constraint[l];
        if (k < 0) {
          CHECK(wc.a[l] == -1);
          CHECK(wc.b[l] == -1);
          CHECK((wc.move_a >> l & 1u) == 0u);
          for (int j = 0; j < wc.count; ++j) CHECK(s.soft.wide_points[wc.first + j].normal_mass[l] == 0.0);
          continue;
        }
        ++used;
        ++seen[k];
        CHECK(k >= s.graph.colour_start[g]);
        CHECK(k < s.graph.colour_start[g + 1]);
        const contact::Constraint<2>& c = s.graph.constraints[k];
        if (g + 2 < int(s.soft.wide_start.size())) CHECK(c.count <= last_count);  // most points first in a colour
        last_count = c.count;
        most = std::max(most, c.count);
        CHECK(wc.a[l] == c.a);
        CHECK(wc.b[l] == c.b);
        CHECK(bool(wc.move_a >> l & 1u) == !s.solver_bodies[c.a].frozen);
        CHECK(bool(wc.move_b >> l & 1u) == !s.solver_bodies[c.b].frozen);
        CHECK(wc.normal[1][l] == 0.8);
        CHECK(wc.inv_mass_a[l] == s.masses[c.a].inv_mass);
        CHECK(wc.iso_b[l] == s.masses[c.b].iso_inv_inertia);
        for (int j = 0; j < wc.count; ++j) {
          const contact::WidePoint<2>& q = s.soft.wide_points[wc.first + j];
          if (j >= c.count) {
            CHECK(q.normal_mass[l] == 0.0);
            CHECK(q.friction[l] == 0.0);
            continue;
          }
          const contact::PointConstraint<2>& p = s.paper.points[c.first + j];
          CHECK(q.normal_mass[l] == p.normal_mass);
          CHECK(q.normal_impulse[l] == p.normal_impulse);
          CHECK(q.separation[l] == p.separation);
          CHECK(q.jn_a[0][l] == p.jn_a[0]);
          // 2D keeps friction along t = (-0.8, 0.6) alone (wide.hpp), worked out by hand from the
          // points above (id = p.tangent_impulse[0]): t . (id, -id) = -1.4 id; t^T M t with M = [id 1;
          // 2 id] is 0.64 id + 0.36 id - 0.48 (1 + 2); jt_b = n . rb = 0.6 (-id) + 0.8 * 3.
          const double id = p.tangent_impulse[0];
          CHECK(q.tangent_impulse[l] == Approx(-1.4 * id).margin(1e-12));
          CHECK(q.tangent_mass[l] == Approx(id - 1.44).margin(1e-12));
          CHECK(q.jt_b[l] == Approx(-0.6 * id + 2.4).margin(1e-12));
          CHECK(q.jt_a[l] == 0.0);  // ra = 0
        }
      }
      CHECK(wc.count == most);
      // Only the uncoloured group goes one to a wide constraint.
      const int left = s.graph.colour_start[g + 1] - s.graph.colour_start[g] - (w - s.soft.wide_start[g]) * L;
      CHECK(used == (g + 2 == int(s.soft.wide_start.size()) ? 1 : std::min(L, left)));
      // A moving body that is not isotropic brings its inverse inertia matrix along.
      const bool general = (wc.a[0] == 1);
      CHECK((wc.inertia >= 0) == general);
      if (general) CHECK(s.soft.wide_inertia[wc.inertia].a[0][0] == 7.0);
    }
  }
  CHECK(s.soft.wide_points.size() == std::size_t(slots));
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  // The uncoloured group keeps its order.
  CHECK(s.soft.wide[3].constraint[0] == colour0 + 1);
  CHECK(s.soft.wide[4].constraint[0] == colour0 + 2);
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

namespace {

// A random contact state for one pass: a frozen ground (body 0), a frozen moving kinematic body (1),
// and dynamic bodies with isotropic inverse inertias (inertia 0), general ones (1) or either (2). `coloured`
// constraints share no moving body (colour 0); three more share body 2 (the uncoloured group). Every
// point is consistent with its bodies (Jacobian rows, effective masses) and starts with random
// impulses, separations, friction and slip. Every body but the ground has moved and turned a little
// since the step began (dp, dq), which the relax pass's separations follow.
template <int N>
contact::ContactState<N> random_pass_state(std::mt19937& rng, int coloured, int inertia) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  contact::ContactState<N> s;
  const int bodies = 2 * coloured + 2;
  s.solver_bodies.resize(bodies);
  s.masses.resize(bodies);
  for (int i = 0; i < bodies; ++i) {
    contact::SolverBody<N>& b = s.solver_bodies[i];
    contact::BodyMass<N>& m = s.masses[i];
    b.v = random_vector<N>(rng);
    for (int k = 0; k < kBiv<N>; ++k) b.w.c[k] = u(rng);
    if (i > 0) {
      b.dp = 0.01 * random_vector<N>(rng);
      Mat<N> skew = Mat<N>::Zero();  // a turn of a few hundredths of a radian: Cayley's (1 - A)^-1 (1 + A)
      for (int r = 0; r < N; ++r)
        for (int c = r + 1; c < N; ++c) skew(r, c) = -(skew(c, r) = 0.03 * u(rng));
      b.dq = (Mat<N>::Identity() - skew).inverse() * (Mat<N>::Identity() + skew);
    }
    if (i < 2) {  // frozen: only read
      b.frozen = true;
      m.isotropic = true;
      if (i == 0) b.v.setZero();
      continue;
    }
    m.inv_mass = 0.5 + unit(rng);
    if (inertia == 0 || (inertia == 2 && rng() % 2 == 0)) {
      m.isotropic = true;
      m.iso_inv_inertia = 0.5 + unit(rng);
      m.inv_inertia = m.iso_inv_inertia * BivMat<N>::Identity();
    } else {
      m.inv_inertia = random_inverse_inertia<N>(rng);
      m.iso_inv_inertia = m.inv_inertia(0, 0);
    }
  }
  const auto add = [&](int a, int b) {
    contact::Constraint<N> c;
    c.a = a;
    c.b = b;
    c.first = int(s.paper.points.size());
    c.count = 1 + int(rng() % kMaxManifoldPoints<N>);
    c.normal = random_vector<N>(rng).normalized();
    c.pair = int(s.list.pairs.size());  // (unpack_wide keeps the impulses in it)
    s.list.pairs.emplace_back();
    s.list.pairs.back().manifold.count = c.count;
    for (int k = 0; k < c.count; ++k) s.list.pairs.back().manifold.points[k].id = 100 + k;
    const contact::BodyMass<N>& sa = s.masses[a];
    const contact::BodyMass<N>& sb = s.masses[b];
    for (int k = 0; k < c.count; ++k) {
      contact::PointConstraint<N> p;
      p.ra = 0.5 * random_vector<N>(rng);
      p.rb = 0.5 * random_vector<N>(rng);
      s.list.pairs.back().arm_a[k] = p.ra;  // (as build_constraint: the points' arms are the pair's)
      s.list.pairs.back().arm_b[k] = p.rb;
      contact::set_effective_masses(
          p, Mat<N>((sa.inv_mass + sb.inv_mass) * Mat<N>::Identity() + contact::angular_mass_term(sa, p.ra) +
                    contact::angular_mass_term(sb, p.rb)),
          c.normal);
      p.jn_a = outer<N>(p.ra, c.normal).c;
      p.jn_b = outer<N>(p.rb, c.normal).c;
      p.dn_a = contact::inverse_inertia_times(sa, p.jn_a);
      p.dn_b = contact::inverse_inertia_times(sb, p.jn_b);
      p.separation = 0.02 * u(rng);
      p.base_separation = 0.02 * u(rng);
      p.normal_impulse = rng() % 4 == 0 ? 0.0 : unit(rng);
      const Vec<N> t = random_vector<N>(rng);
      p.tangent_impulse = rng() % 4 == 0 ? Vec<N>::Zero() : Vec<N>(0.3 * (t - t.dot(c.normal) * c.normal));
      p.friction = rng() % 5 == 0 ? 0.0 : unit(rng);
      p.sliding = rng() % 3 == 0;
      const Vec<N> d = random_vector<N>(rng);
      if (p.sliding) p.slip_direction = (d - d.dot(c.normal) * c.normal).normalized();
      s.paper.points.push_back(p);
    }
    s.graph.constraints.push_back(c);
  };
  for (int k = 0; k < coloured; ++k) add(k % 3 == 0 ? int(k % 2) : 2 + 2 * k, 3 + 2 * k);
  for (int k = 0; k < 3; ++k) add(2, 3 + 2 * k);
  s.graph.colour_start = {0, coloured, coloured + 3};
  s.soft.bias_rate = 40.0;
  s.soft.mass_scale = 0.8;
  s.soft.impulse_scale = 0.2;
  return s;
}

// Point k of constraint c as unpack_wide leaves it in the pair: the last sub-step's normal and
// tangential impulses and the step's total normal impulse.
template <int N>
struct Unpacked {
  double normal, total;
  Vec<N> tangent;
};
template <int N>
Unpacked<N> unpacked(const contact::ContactState<N>& s, const contact::Constraint<N>& c, int k) {
  const contact::Pair<N>& pair = s.list.pairs[c.pair];
  return {pair.warm_normal[k], pair.normal_impulse[k], pair.warm_tangent[k]};
}

// The soft step's pass one point at a time, as it was before the lanes (03c200d): per constraint the
// normal impulses, then friction through friction_update, the scalar code the paper's solver uses. The
// relax pass first takes each point's separation from where its bodies have carried its two ends:
// base + n . ((dp_b + dq_b rb) - (dp_a + dq_a ra)).
template <int N>
void reference_pass(contact::ContactState<N>& s, const ContactSettings& settings, double h, bool use_bias) {
  for (const contact::Constraint<N>& c : s.graph.constraints) {
    contact::SolverBody<N>& a = s.solver_bodies[c.a];
    contact::SolverBody<N>& b = s.solver_bodies[c.b];
    const contact::BodyMass<N>& ma = s.masses[c.a];
    const contact::BodyMass<N>& mb = s.masses[c.b];
    const Vec<N>& n = c.normal;
    for (int k = 0; k < c.count && !use_bias; ++k) {
      contact::PointConstraint<N>& p = s.paper.points[c.first + k];
      p.separation = p.base_separation + n.dot(Vec<N>((b.dp + b.dq * p.rb) - (a.dp + a.dq * p.ra)));
    }
    for (int k = 0; k < c.count; ++k) {
      contact::PointConstraint<N>& p = s.paper.points[c.first + k];
      double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
      if (p.separation > 0.0) {
        bias = p.separation / h;
      } else if (use_bias) {
        bias = std::max(s.soft.mass_scale * s.soft.bias_rate * p.separation, -settings.contact_push_speed);
        mass_scale = s.soft.mass_scale;
        impulse_scale = s.soft.impulse_scale;
      }
      const double un = n.dot(b.v - a.v) + p.jn_b.dot(b.w.c) - p.jn_a.dot(a.w.c);
      const double next = std::max(
          p.normal_impulse - p.normal_mass * (mass_scale * un + bias) - impulse_scale * p.normal_impulse, 0.0);
      const double change = next - p.normal_impulse;
      p.normal_impulse = next;
      p.normal_total += change;
      contact::apply_normal_impulse(a, ma, b, mb, n, change, p.dn_a, p.dn_b);
    }
    for (int k = 0; k < c.count; ++k) {
      contact::PointConstraint<N>& p = s.paper.points[c.first + k];
      if (!(p.friction > 0.0) || (p.normal_impulse <= 0.0 && p.tangent_impulse.isZero(0.0))) continue;
      const Vec<N> u = contact::relative_velocity(a, b, p);
      const Vec<N> next = contact::friction_update(p, n, Vec<N>(u - n.dot(u) * n));
      const Vec<N> change = next - p.tangent_impulse;
      p.tangent_impulse = next;
      contact::apply_impulse(a, ma, b, mb, p, change);
    }
  }
}

}  // namespace

// The lanes against the scalar pass: same velocities and impulses to round-off, for isotropic and
// general inertias, frozen bodies, lanes left empty or short of points, friction in and outside the
// cone, penetrating and separated points, with and without the push (solve and relax).
TEMPLATE_TEST_CASE_SIG("a pass over the lanes does what the scalar pass does, point for point (2D-6D)",
                       "[contact][solver_algebra]", ((int N), N), 2, 3, 4, 5, 6) {
  std::mt19937 rng(150 + N);
  const ContactSettings settings;
  int clamped = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const bool use_bias = trial % 2 == 0;
    contact::ContactState<N> lanes = random_pass_state<N>(rng, 3 + trial % 11, trial % 3);
    contact::ContactState<N> reference = lanes;
    contact::pack_wide(lanes);
    contact::solve_contacts(lanes, settings, 1.0 / 480.0, use_bias);
    contact::unpack_wide(lanes);
    reference_pass(reference, settings, 1.0 / 480.0, use_bias);
    // Each value is a chain of up to 2^(N-1) point updates of sums of a few dozen products of numbers of
    // order 1 (and the cone projection's Newton, to 1e-13): the two orders of summation agree to about
    // 1e-13; a wrong index, sign or lane is off by order 0.1.
    const double tol = 1e-10;
    for (std::size_t i = 0; i < lanes.solver_bodies.size(); ++i) {
      INFO("trial " << trial << ", body " << i);
      CHECK((lanes.solver_bodies[i].v - reference.solver_bodies[i].v).norm() <= tol);
      CHECK((lanes.solver_bodies[i].w.c - reference.solver_bodies[i].w.c).norm() <= tol);
    }
    // Frozen bodies are never written.
    CHECK(lanes.solver_bodies[0].v == reference.solver_bodies[0].v);
    CHECK(lanes.solver_bodies[1].v == reference.solver_bodies[1].v);
    // (unpack_wide keeps each point's impulses, total, feature id and lever arm in its pair, slot by slot.)
    for (const contact::Constraint<N>& c : lanes.graph.constraints) {
      const contact::Pair<N>& pair = lanes.list.pairs[c.pair];
      REQUIRE(pair.warm_count == c.count);
      for (int k = 0; k < c.count; ++k) {
        INFO("trial " << trial << ", point " << c.first + k);
        const Unpacked<N> got = unpacked(lanes, c, k);
        const contact::PointConstraint<N>& p = reference.paper.points[c.first + k];
        CHECK(std::abs(got.normal - p.normal_impulse) <= tol);
        CHECK(std::abs(got.total - p.normal_total) <= tol);
        CHECK((got.tangent - p.tangent_impulse).norm() <= tol);
        CHECK(pair.warm_id[k] == std::uint64_t(100 + k));
        CHECK(pair.warm_arm[k] == p.ra);
        if (p.friction > 0.0 && p.tangent_impulse.norm() >= p.friction * p.normal_impulse * (1.0 - 1e-12) &&
            p.normal_impulse > 0.0)
          ++clamped;
      }
    }
  }
  CHECK(clamped > 10);  // the cone's slow path was exercised
}

// The passes in 4-lane packs, on AVX2 and on AVX-512 (2D, 3D), against the same passes in 2-lane packs:
// the lanes and the operations are the same, so every bit must be (wide.hpp, LaneTypes; lanes_x86.cpp).
TEMPLATE_TEST_CASE_SIG("a pass in AVX2 or AVX-512 lanes gives the bits of a pass in SSE2 lanes (2D, 3D)",
                       "[contact][solver_algebra][determinism]", ((int N), N), 2, 3) {
  const auto wide = GENERATE(contact::Lanes::Avx2, contact::Lanes::Avx512);
  const char* name = wide == contact::Lanes::Avx2 ? "AVX2" : "AVX-512";
  INFO(name);
  if (!contact::lanes_supported(wide)) {
    WARN("this CPU (or build) has no " << name << ": nothing to compare");
    return;
  }
  std::mt19937 rng(170 + N);
  const ContactSettings settings;
  int differing_from_start = 0;
  for (int trial = 0; trial < 60; ++trial) {
    contact::ContactState<N> sse2 = random_pass_state<N>(rng, 3 + trial % 11, trial % 3);
    contact::pack_wide(sse2);
    contact::ContactState<N> packed = sse2;
    sse2.soft.lanes = contact::Lanes::Sse2;
    packed.soft.lanes = wide;
    const auto start = sse2.solver_bodies;
    for (const bool use_bias : {true, false, true}) {
      contact::solve_contacts(sse2, settings, 1.0 / 480.0, use_bias);
      contact::solve_contacts(packed, settings, 1.0 / 480.0, use_bias);
    }
    INFO("trial " << trial);
    REQUIRE(sse2.soft.wide_points.size() == packed.soft.wide_points.size());
    CHECK(std::memcmp(sse2.soft.wide_points.data(), packed.soft.wide_points.data(),
                      sse2.soft.wide_points.size() * sizeof(contact::WidePoint<N>)) == 0);
    CHECK(std::memcmp(sse2.soft.wide_cold.data(), packed.soft.wide_cold.data(),
                      sse2.soft.wide_cold.size() * sizeof(contact::WidePointCold<N>)) == 0);
    for (std::size_t i = 0; i < sse2.solver_bodies.size(); ++i) {
      CHECK(std::memcmp(sse2.solver_bodies[i].v.data(), packed.solver_bodies[i].v.data(), sizeof(double) * N) == 0);
      CHECK(std::memcmp(sse2.solver_bodies[i].w.c.data(), packed.solver_bodies[i].w.c.data(),
                        sizeof(double) * kBiv<N>) == 0);
      if (sse2.solver_bodies[i].v != start[i].v) ++differing_from_start;
    }
  }
  CHECK(differing_from_start > 100);  // the passes did change the velocities they compared
}

// After the first sub-step the soft step warm starts body by body (soft_step.cpp, warm_start_substep):
// warm_v and warm_w must be the velocity change of every point's accumulated impulse applied through
// its lever arms, here applied point by point by the scalar code of the paper's solver (apply_impulse),
// and each point's normal_total the sum of its impulses at the end of every sub-step. The scene has
// cubes (isotropic inertia) and, from 3D on, a cuboid whose inertia is a full matrix, stacked on the
// ground and on each other, moving down and turning so that every point takes normal and friction
// impulses. Tolerance: each value is a sum of a few dozen products of numbers of order 1-100, formed in
// two orders (per sub-step differences against point by point): 1e-12 relative to the largest; a lost
// pass or point is off by order 1%.
TEMPLATE_TEST_CASE_SIG("a sub-step's warm start body by body equals every point's impulse applied point by point "
                       "(2D-4D)",
                       "[contact][solver_algebra]", ((int N), N), 2, 3, 4) {
  ContactBodies<N> scene;
  std::vector<Body<N>>& bodies = scene.bodies;
  scene.add_ground();
  const auto cube = std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(0.5)));
  Vec<N> half = Vec<N>::Constant(0.4);
  half[0] = 0.9;
  half[1] = 0.3;
  scene.add(std::make_shared<const Shape<N>>(Shape<N>::box(half)), BodyType::Dynamic, 0.299 * Vec<N>::Unit(1));
  scene.add(cube, BodyType::Dynamic, Vec<N>(0.3 * Vec<N>::Unit(0) + 1.098 * Vec<N>::Unit(1)));
  scene.add(cube, BodyType::Dynamic, Vec<N>(0.4 * Vec<N>::Unit(0) + 2.097 * Vec<N>::Unit(1)));
  scene.add(cube, BodyType::Dynamic, Vec<N>(3.0 * Vec<N>::Unit(0) + 0.499 * Vec<N>::Unit(1)));
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    bodies[i].velocity = Vec<N>::Zero();
    bodies[i].velocity[0] = 0.05 * double(i);
    bodies[i].velocity[1] = -0.3;
    bodies[i].angular_velocity.c[0] = 0.2 - 0.1 * double(i);
  }
  contact::ContactState<N> s;
  for (int i = 0; i < int(bodies.size()); ++i) contact::add_body(s, bodies, scene.shapes, i);
  const ContactSettings settings;
  const double h = 1.0 / 60.0 / settings.substeps;
  contact::find_contacts(s, bodies, scene.shapes, scene.materials, settings, 1.0 / 60.0);
  REQUIRE(s.graph.constraints.size() == 4);
  contact::prepare_soft_step(s, bodies, settings, h);
  const int total = s.graph.constraints.back().first + s.graph.constraints.back().count;
  std::vector<double> summed(total, 0.0);  // each point's impulse, summed over the sub-steps
  for (int sub = 0; sub < settings.substeps; ++sub) {
    // gravity (the sub-steps' velocities are the solver bodies')
    for (std::size_t i = 1; i < bodies.size(); ++i) s.solver_bodies[i].v[1] -= 9.81 * h;
    if (sub > 0) {
      contact::unpack_wide(s);
      std::vector<contact::SolverBody<N>> expected = s.solver_bodies;
      for (auto& b : expected) {
        b.v.setZero();
        b.w = Bivector<N>{};
      }
      for (const contact::Constraint<N>& c : s.graph.constraints)
        for (int k = 0; k < c.count; ++k) {
          const Unpacked<N> u = unpacked(s, c, k);
          const Vec<N> j = u.normal * c.normal + u.tangent;
          contact::PointConstraint<N> lever;  // (apply_impulse reads the lever arms alone)
          lever.ra = s.list.pairs[c.pair].arm_a[k];
          lever.rb = s.list.pairs[c.pair].arm_b[k];
          contact::apply_impulse(expected[c.a], s.masses[c.a], expected[c.b], s.masses[c.b], lever, j);
        }
      double scale = 0.0;
      for (const auto& b : expected) scale = std::max({scale, b.v.cwiseAbs().maxCoeff(), b.w.c.cwiseAbs().maxCoeff()});
      REQUIRE(scale > 0.01);  // the impulses do move the bodies
      for (std::size_t i = 1; i < bodies.size(); ++i) {
        INFO("sub-step " << sub << ", body " << i);
        CHECK((s.solver_bodies[i].warm_v - expected[i].v).cwiseAbs().maxCoeff() <= 1e-12 * scale);
        CHECK((s.solver_bodies[i].warm_w.c - expected[i].w.c).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      }
    }
    contact::solve_substep(s, bodies, settings, h, true);
    contact::track_substep_motion(s, bodies);
    contact::solve_substep(s, bodies, settings, h, false);
    contact::flush_pass_change(s);  // (gravity changes the velocities next, as World's integration would)
    contact::unpack_wide(s);
    for (const contact::Constraint<N>& c : s.graph.constraints)
      for (int k = 0; k < c.count; ++k) summed[c.first + k] += unpacked(s, c, k).normal;
  }
  int loaded = 0;
  double largest = 0.0;
  for (const double x : summed) largest = std::max(largest, x);
  for (const contact::Constraint<N>& c : s.graph.constraints)
    for (int k = 0; k < c.count; ++k) {
      INFO("point " << c.first + k);
      CHECK(std::abs(unpacked(s, c, k).total - summed[c.first + k]) <= 1e-12 * largest);
      if (summed[c.first + k] > 0.0) ++loaded;
    }
  CHECK(loaded >= total / 2);
}
