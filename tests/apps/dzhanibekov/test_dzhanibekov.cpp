// The torque-free Dzhanibekov study (paper section 9; docs/dzhanibekov.md), run through World exactly as
// wedge-dzhanibekov runs it (the cases come from apps/dzhanibekov/cases.hpp), with World's default
// settings (implicit midpoint gyroscopic step, rotor repair every step) unless stated.
//
// What is checked, and why the bounds are what they are:
//  * World's body-frame equations are those of section 9 (up to the sign convention noted below).
//  * 3D, intermediate axis: the rotation flips, periodically, at the times an independent RK4 integration of
//    the body-frame Euler equations gives (0.05 s tolerance; measured agreement ~0.01 s over 4 flips), with
//    a full reversal each time. Energy and |L| are conserved to 1e-8 relative (measured 2e-10 in 60 s at
//    h = 1e-4; round-off of the Newton solves and rotor repair).
//  * The same with the paper's implicit Euler: the flip times hold; energy and |L| only decrease, by less
//    than 0.5% / 0.25% in 30 s at h = 1e-4 (measured 0.19% / 0.10%; the loss is first order in h).
//  * 3D, smallest and largest moment: stays near the initial rotation (perturbation 1% stays below 3%;
//    measured 1.75%), the main component never changes sign.
//  * 4D (c), angular velocity inside the 3D subspace yzw: the xy, xz, xw components stay exactly 0 at every
//    step and the yz rotation flips like the 3D one (RK4 flip times to 0.05 s).
//  * 4D (c'), angular velocity inside the xyz subspace, and (b), the pure xy rotation: exactly invariant,
//    with rotor repair off and with it on (every step; since 4818c4f the repair keeps a rotation confined
//    to a subspace exactly inside it, before that it leaked round-off into w that grew to O(1)). (c') flips
//    like 3D (RK4 flip times to 0.05 s); (b) never moves off the pure xy rotation.
//  * 4D (a): the dual plane zw starts at exactly 0 and picks up rotation of the order of the perturbations.
//  * 4D (d): a perturbation out of the subspace of (c) grows to O(1) (yz is intermediate in xyz as well).
// Runtime ~2.5 s in Release.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../../../apps/dzhanibekov/cases.hpp"

namespace {

namespace dz = wedge::dzhanibekov;
using wedge::Bivector;
using wedge::BivMat;

// Times at which component k of the recorded body-frame angular velocity changes sign.
template <int N>
std::vector<double> sign_changes(const std::vector<dz::Sample<N>>& s, int k) {
  std::vector<double> t;
  for (std::size_t i = 1; i < s.size(); ++i)
    if ((s[i].w_body[k] > 0.0) != (s[i - 1].w_body[k] > 0.0)) t.push_back(s[i].time);
  return t;
}

// Independent reference: RK4 on the body-frame Euler equations I dw/dt = w x I w (diagonal I), returning
// the (linearly interpolated) sign-change times of component k.
template <int N>
std::vector<double> reference_sign_changes(const dz::Case<N>& c, double h, double duration, int k) {
  const BivMat<N> inertia = dz::box_inertia<N>(c.sides, c.mass);
  auto rhs = [&](const Bivector<N>& w) {
    const Bivector<N> iw = Bivector<N>::from(inertia * w.c);
    return Bivector<N>::from(wedge::commutator(w, iw).c.cwiseQuotient(inertia.diagonal()));
  };
  std::vector<double> t;
  Bivector<N> w = c.w0;
  const long steps = std::lround(duration / h);
  for (long s = 0; s < steps; ++s) {
    const Bivector<N> k1 = rhs(w), k2 = rhs(w + k1 * (h / 2)), k3 = rhs(w + k2 * (h / 2)), k4 = rhs(w + k3 * h);
    const Bivector<N> next = w + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
    if ((next[k] > 0.0) != (w[k] > 0.0)) t.push_back(double(s) * h + h * w[k] / (w[k] - next[k]));
    w = next;
  }
  return t;
}

// Energy and |L| stay within `tolerance` (relative) of their initial values over the whole run.
template <int N>
void check_conserved(const std::vector<dz::Sample<N>>& s, double tolerance) {
  double e_dev = 0.0, l_dev = 0.0;
  for (const auto& x : s) {
    e_dev = std::max(e_dev, std::abs(x.energy / s[0].energy - 1.0));
    l_dev = std::max(l_dev, std::abs(x.momentum / s[0].momentum - 1.0));
  }
  INFO("energy drift " << e_dev << ", |L| drift " << l_dev);
  CHECK(e_dev < tolerance);
  CHECK(l_dev < tolerance);
}

// Implicit Euler: energy never increases beyond round-off, and the largest relative losses of energy and
// |L| stay below the bounds.
template <int N>
void check_dissipation(const std::vector<dz::Sample<N>>& s, double max_energy_loss, double max_momentum_loss) {
  double e_loss = 0.0, l_loss = 0.0;
  bool monotone = true;
  for (std::size_t i = 1; i < s.size(); ++i) {
    e_loss = std::max(e_loss, 1.0 - s[i].energy / s[0].energy);
    l_loss = std::max(l_loss, 1.0 - s[i].momentum / s[0].momentum);
    if (s[i].energy > s[i - 1].energy * (1.0 + 1e-13)) monotone = false;
  }
  INFO("energy loss " << e_loss << ", |L| loss " << l_loss);
  CHECK(monotone);
  CHECK(e_loss > 0.0);
  CHECK(e_loss < max_energy_loss);
  CHECK(l_loss < max_momentum_loss);
}

template <int N>
int index(int i, int j) {
  return Bivector<N>::index(i, j);
}

}  // namespace

TEST_CASE("World's body-frame equations are the 4D Euler equations of section 9", "[dzhanibekov]") {
  // Finite difference of one tiny World step against
  //   I_ij dw_ij/dt = (I_ik - I_jk) w_ik w_jk + (I_im - I_jm) w_im w_jm     (k, m the other two indices).
  // Section 9 prints the right-hand side with the opposite overall sign; with the paper's own conventions
  // (dR/dt = -w R / 2, eq. 5 with the commutator A x B = (AB - BA)/2) the body-frame equation is
  // I dw/dt = w x I w, which gives the sign above. The sign flip is w -> -w (time reversal) and does not
  // change which rotations are stable.
  const BivMat<4> inertia = dz::box_inertia<4>(dz::kCuboid4, 1.0);
  const Bivector<4> w0 = dz::bivector<4>({{0, 1, 1.3}, {0, 2, -0.7}, {0, 3, 0.4}, {1, 2, 2.1}, {1, 3, -1.6}, {2, 3, 0.9}});
  wedge::World<4> world;
  wedge::BodyDef<4> def;
  def.inertia = inertia;
  def.angular_velocity = w0;
  const wedge::BodyId id = world.add_body(def);
  const double h = 1e-7;
  world.step(h);
  const Bivector<4> w1 = wedge::rotate_inverse(world.body(id).rotor, world.body(id).angular_velocity);
  auto moment = [&](int a, int b) { return inertia(index<4>(std::min(a, b), std::max(a, b)), index<4>(std::min(a, b), std::max(a, b))); };
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      int k = -1, m = -1;
      for (int a = 0; a < 4; ++a)
        if (a != i && a != j) (k < 0 ? k : m) = a;
      const double expected = (moment(i, k) - moment(j, k)) * w0(i, k) * w0(j, k) +
                              (moment(i, m) - moment(j, m)) * w0(i, m) * w0(j, m);
      const double measured = moment(i, j) * (w1[index<4>(i, j)] - w0[index<4>(i, j)]) / h;
      INFO("plane " << i << j);
      CHECK(measured == Approx(expected).epsilon(1e-5).margin(1e-9));
    }
}

// Runs the 3D intermediate-axis case and checks the flips against RK4: periodic, a full reversal each time.
std::vector<dz::Sample<3>> check_3d_flip(const wedge::WorldSettings<3>& settings) {
  const dz::Case<3> c = dz::case_3d_flip();  // box (1, 2, 3), spin 5 rad/s in xz, 1e-3 perturbation
  const int xz = index<3>(0, 2);
  const double h = 1e-4, duration = 30.0;
  const auto s = dz::simulate<3>(c, h, duration, 1, settings);
  const auto flips = sign_changes<3>(s, xz);
  const auto reference = reference_sign_changes<3>(c, h, duration, xz);
  REQUIRE(flips.size() >= 4);
  REQUIRE(flips.size() == reference.size());
  for (std::size_t i = 0; i < flips.size(); ++i) CHECK(std::abs(flips[i] - reference[i]) < 0.05);
  // Periodic: equal intervals between flips (to 1%).
  for (std::size_t i = 2; i < flips.size(); ++i)
    CHECK((flips[i] - flips[i - 1]) == Approx(flips[1] - flips[0]).epsilon(0.01));
  // A full reversal each time: between flips w_xz reaches -0.99 or +0.99 of the spin.
  for (std::size_t i = 0; i + 1 < flips.size(); ++i) {
    double lo = 1e9, hi = -1e9;
    for (const auto& x : s)
      if (x.time > flips[i] && x.time < flips[i + 1]) {
        lo = std::min(lo, x.w_body[xz]);
        hi = std::max(hi, x.w_body[xz]);
      }
    CHECK(std::max(-lo, hi) > 0.99 * dz::kSpin);
  }
  return s;
}

TEST_CASE("3D: rotation in the intermediate plane flips periodically, at the RK4 reference times", "[dzhanibekov]") {
  SECTION("implicit midpoint (World's default): energy and |L| conserved") {
    check_conserved<3>(check_3d_flip({}), 1e-8);
  }
  SECTION("implicit Euler (the paper's): energy and |L| slowly lost") {
    wedge::WorldSettings<3> euler;
    euler.gyroscopic_method = wedge::GyroscopicMethod::ImplicitEuler;
    check_dissipation<3>(check_3d_flip(euler), 5e-3, 2.5e-3);
  }
}

TEST_CASE("3D: rotation in the smallest or largest moment plane is stable", "[dzhanibekov]") {
  for (const dz::Case<3>& c : {dz::case_3d_stable_small(), dz::case_3d_stable_large()}) {
    INFO(c.id);
    int main = 0;
    c.w0.c.cwiseAbs().maxCoeff(&main);
    const auto s = dz::simulate<3>(c, 5e-4, 30.0);
    double min_main = 1e9, max_other = 0.0;
    for (const auto& x : s) {
      min_main = std::min(min_main, x.w_body[main]);
      for (int k = 0; k < 3; ++k)
        if (k != main) max_other = std::max(max_other, std::abs(x.w_body[k]));
    }
    CHECK(min_main > 0.99 * dz::kSpin);     // never turns over
    CHECK(max_other < 0.03 * dz::kSpin);    // the 1% perturbation stays small
    CHECK(sign_changes<3>(s, main).empty());
    check_conserved<3>(s, 1e-8);
  }
}

TEST_CASE("4D case (c): angular velocity in a 3D subspace stays in it exactly and flips like 3D", "[dzhanibekov]") {
  const dz::Case<4> c = dz::case_4d_c();  // yzw subspace, spin in yz
  const int yz = index<4>(1, 2);
  const double h = 1e-4, duration = 30.0;
  const auto s = dz::simulate<4>(c, h, duration);  // every step recorded
  bool exact = true;
  for (const auto& x : s)
    for (int j = 1; j < 4; ++j) exact = exact && x.w_body[index<4>(0, j)] == 0.0;
  CHECK(exact);
  const auto flips = sign_changes<4>(s, yz);
  const auto reference = reference_sign_changes<4>(c, h, duration, yz);
  REQUIRE(flips.size() >= 8);
  REQUIRE(flips.size() == reference.size());
  for (std::size_t i = 0; i < flips.size(); ++i) CHECK(std::abs(flips[i] - reference[i]) < 0.05);
  check_conserved<4>(s, 1e-8);
}

TEST_CASE("4D: the xyz subspace (c') and the pure xy rotation (b) are exactly invariant, with or without rotor repair", "[dzhanibekov]") {
  wedge::WorldSettings<4> no_repair;
  no_repair.rotor_repair_interval = 1 << 30;
  const wedge::WorldSettings<4> repair;  // World's default: repair every step
  SECTION("xyz subspace (case c'), no repair") {
    const auto s = dz::simulate<4>(dz::case_4d_c_xyz(), 5e-4, 15.0, 1, no_repair);
    bool exact = true;
    for (const auto& x : s)
      for (int i = 0; i < 3; ++i) exact = exact && x.w_body[index<4>(i, 3)] == 0.0;
    CHECK(exact);
    CHECK(sign_changes<4>(s, index<4>(1, 2)).size() >= 4);
  }
  SECTION("xyz subspace (case c'), repair every step: exact, and flips like 3D") {
    // Before 4818c4f the repair leaked round-off into xw, yw, zw here, and it grew to O(1) in ~9 s.
    const dz::Case<4> c = dz::case_4d_c_xyz();
    const int yz = index<4>(1, 2);
    const double h = 1e-4, duration = 30.0;
    const auto s = dz::simulate<4>(c, h, duration, 1, repair);
    bool exact = true;
    for (const auto& x : s)
      for (int i = 0; i < 3; ++i) exact = exact && x.w_body[index<4>(i, 3)] == 0.0;
    CHECK(exact);
    const auto flips = sign_changes<4>(s, yz);
    const auto reference = reference_sign_changes<4>(c, h, duration, yz);
    REQUIRE(flips.size() >= 8);
    REQUIRE(flips.size() == reference.size());
    for (std::size_t i = 0; i < flips.size(); ++i) CHECK(std::abs(flips[i] - reference[i]) < 0.05);
    check_conserved<4>(s, 1e-8);
  }
  for (const bool with_repair : {false, true}) {
    DYNAMIC_SECTION("pure xy rotation (case b) is a fixed point, " << (with_repair ? "repair every step" : "no repair")) {
      // With repair, before 4818c4f, round-off reached xw and yw and the xy rotation flipped after ~12 s.
      const auto s = dz::simulate<4>(dz::case_4d_b(), 5e-4, 15.0, 1, with_repair ? repair : no_repair);
      bool exact = true;
      for (const auto& x : s)
        for (int k = 1; k < 6; ++k) exact = exact && x.w_body[k] == 0.0;
      CHECK(exact);
      // Only the magnitude moves, by the round-off of the sandwich products (4e-12 relative in 30000 steps).
      CHECK(s.back().w_body[index<4>(0, 1)] == Approx(dz::kSpin).epsilon(1e-9));
    }
  }
}

TEST_CASE("4D case (a): the dual plane zw picks up rotation, xy flips", "[dzhanibekov]") {
  const dz::Case<4> c = dz::case_4d_a();
  const int xy = index<4>(0, 1), zw = index<4>(2, 3);
  REQUIRE(c.w0[zw] == 0.0);
  const double h = 1e-4, duration = 30.0;
  const auto s = dz::simulate<4>(c, h, duration, 10);
  double max_zw = 0.0;
  for (const auto& x : s) max_zw = std::max(max_zw, std::abs(x.w_body[zw]));
  CHECK(max_zw > 0.5 * dz::kPerturb);  // measured 1.4x the perturbation
  CHECK(max_zw < 0.1 * dz::kSpin);
  // xy is intermediate in the xyw subspace: it flips, at the RK4 times (0.1 s after 6 flips).
  const auto flips = sign_changes<4>(s, xy);
  const auto reference = reference_sign_changes<4>(c, h, duration, xy);
  REQUIRE(flips.size() >= 5);
  REQUIRE(flips.size() == reference.size());
  for (std::size_t i = 0; i < flips.size(); ++i) CHECK(std::abs(flips[i] - reference[i]) < 0.1);
  check_conserved<4>(s, 1e-8);
}

TEST_CASE("4D case (d): a perturbation out of the subspace of (c) grows", "[dzhanibekov]") {
  const auto s = dz::simulate<4>(dz::case_4d_d(), 5e-4, 30.0, 10);
  double max_out = 0.0;
  for (const auto& x : s)
    for (int j = 1; j < 4; ++j) max_out = std::max(max_out, std::abs(x.w_body[index<4>(0, j)]));
  CHECK(max_out > 20.0 * dz::kPerturb);  // from 0.05 to > 1 rad/s (measured ~3.9)
  check_conserved<4>(s, 1e-8);
}
