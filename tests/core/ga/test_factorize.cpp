// Rotor repair by factorisation: it yields exact rotations where scalar normalisation does not (4D+).
#include <catch2/catch.hpp>
#include <random>

#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"

#include "test_util.hpp"

using namespace wedge;

namespace {

// How far an even element is from being a rotor: |R ~R - 1| and the orthogonality defect of x -> R x ~R.
template <int N>
double rotor_defect(const Rotor<N>& r) {
  return (r * reverse(r) - Rotor<N>::identity()).norm();
}
template <int N>
double orthogonality_defect(const Rotor<N>& r) {
  const Mat<N> m = to_matrix(r);
  return (m.transpose() * m - Mat<N>::Identity()).norm();
}

// Drift as an integrator without repair produces it: explicit steps R += -h/2 w R.
template <int N>
Rotor<N> drifted(const Bivector<N>& w, double h, int steps) {
  Rotor<N> r = Rotor<N>::identity();
  for (int i = 0; i < steps; ++i) r += to_even(w) * r * (-0.5 * h);
  return r;
}

}  // namespace

TEST_CASE("4D: scalar normalisation leaves a double-rotation rotor broken, factorisation repairs it",
          "[ga][repair]") {
  // A double rotation (w01 != 0 and w23 != 0) integrated with explicit steps grows a grade-4 error
  // that keeps R ~R away from 1 even after dividing by |R|.
  Bivector<4> w = Bivector<4>::basis(0, 1) * 3.0 + Bivector<4>::basis(2, 3) * 2.0 + Bivector<4>::basis(0, 2) * 0.5;
  const Rotor<4> raw = drifted<4>(w, 1e-3, 2000);
  const Rotor<4> normalised = raw / raw.norm();
  INFO("normalised defect " << rotor_defect(normalised) << ", orthogonality " << orthogonality_defect(normalised));
  CHECK(rotor_defect(normalised) > 1e-3);
  // x -> R x ~R no longer preserves lengths: not a rotation.
  CHECK(orthogonality_defect(normalised) > 1e-5);
  const Multivector<4> x = to_multivector(Vec<4>(1.0, 0.0, 0.0, 0.0));

  const Rotor<4> fixed = repair(raw);
  CHECK(rotor_defect(fixed) < 1e-15 * 8);
  CHECK(orthogonality_defect(fixed) < 1e-15 * 8);
  const Multivector<4> image = to_multivector(fixed) * x * reverse(to_multivector(fixed));
  CHECK((image - grade(image, 1)).norm() < 1e-15 * 8);
  CHECK(std::abs(image.norm() - 1.0) < 1e-15 * 8);
  // Repair moves the rotor no further than the drift itself.
  CHECK((fixed - normalised).norm() < 2 * rotor_defect(normalised));
}

TEST_CASE("3D: a unit quaternion is always a rotor, so normalisation is enough there", "[ga][repair]") {
  const Bivector<3> w = Bivector<3>::basis(0, 1) * 3.0 + Bivector<3>::basis(1, 2) * 2.0;
  const Rotor<3> raw = drifted<3>(w, 1e-3, 2000);
  CHECK(rotor_defect<3>(raw / raw.norm()) < 1e-15 * 8);
}

template <int N>
void check_repair() {
  std::mt19937_64 rng(300 + N);
  std::normal_distribution<double> nd;
  for (int t = 0; t < 200; ++t) {
    const Rotor<N> exact = exp(random_bivector<N>(rng, 2.0));
    Rotor<N> noisy = exact;
    for (int i = 0; i < kEven<N>; ++i) noisy[i] += 1e-7 * nd(rng);
    const Rotor<N> fixed = repair(noisy);
    INFO("N = " << N);
    CHECK(rotor_defect(fixed) < 1e-14);
    CHECK((fixed - exact).norm() < 1e-5);  // the same rotation, with the same sign
    // The factors are unit vectors and their product is the rotor.
    const RotorFactors<N> f = factorize(noisy);
    for (int i = 0; i < f.count; ++i) CHECK(std::abs(f.v[i].norm() - 1.0) < 1e-15 * 4);
    CHECK((compose(f) - fixed).norm() < (N <= 3 ? 1e-14 : 0.0) + 1e-300);  // N <= 3 repairs by scaling
    // An exact rotor is a fixed point (to round-off).
    CHECK((repair(exact) - exact).norm() < 1e-14);
    // rotor_from_matrix recovers the rotation (up to the sign of R).
    const Rotor<N> back = rotor_from_matrix<N>(to_matrix(exact));
    CHECK(std::min((back - exact).norm(), (back + exact).norm()) < 1e-14);
  }
  // Half turns (the b = -a branch) in every plane pair.
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const Rotor<N> half = exp(Bivector<N>::basis(i, j) * (M_PI / 2));
      CHECK((repair(half) - half).norm() < 1e-14);
    }
}

TEST_CASE("repair returns an exact rotor of the same rotation in every dimension", "[ga][repair]") {
  check_repair<2>();
  check_repair<3>();
  check_repair<4>();
  check_repair<5>();
  check_repair<6>();
}

TEST_CASE("repair keeps a rotation confined to a subspace exactly inside it", "[ga][repair]") {
  // A 4D rotation of the xyz subspace, turned by up to 2 pi (the two-leg branch beyond 120 degrees):
  // every rotor component that involves e3 must stay exactly zero, or round-off leaks into w and can grow
  // there (an intermediate-plane instability, docs/dzhanibekov.md).
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  constexpr auto even = ga::Blades<4>::order<ga::Set::Even>();
  for (int t = 0; t < 500; ++t) {
    const double a01 = angle(rng), a02 = angle(rng), a12 = angle(rng);  // (drawn in this order by every compiler)
    const Bivector<4> b = Bivector<4>::basis(0, 1) * a01 + Bivector<4>::basis(0, 2) * a02 + Bivector<4>::basis(1, 2) * a12;
    Rotor<4> noisy = exp(b);
    for (int i = 0; i < 8; ++i)
      if (!(even[i] & 8u)) noisy[i] *= 1.0 + 1e-9 * (i + 1);  // drift inside the subspace only
    const Rotor<4> fixed = repair(noisy);
    for (int i = 0; i < 8; ++i)
      if (even[i] & 8u) CHECK(fixed[i] == 0.0);
    CHECK((fixed * reverse(fixed) - Rotor<4>::identity()).norm() < 1e-14);
  }
}
