// rotor_between_frames (ga/frames.hpp), the paper's successive simple rotors, in 2D-6D: the rotor maps
// every source axis onto its target and is a unit rotor whose matrix is to * from^T (checked against the
// frames themselves, not against another rotor routine); a single-plane turn gives exactly the analytic
// rotor exp(-a/2 e01); half turns (antiparallel axes, where the simple rotor's plane is undefined) and
// nearly half turns work; frames that are not orthonormal or not of one orientation are refused.
// Tolerance 1e-12: each of the N - 1 steps is a handful of products of unit quantities (round-off 1e-15).
#include <catch2/catch.hpp>
#include <bit>
#include <cmath>
#include <random>

#include "convex_oracle.hpp"
#include "test_util.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/frames.hpp"

using namespace wedge;

namespace {

constexpr double kTol = 1e-12;

template <int N>
void check_maps(const Mat<N>& from, const Mat<N>& to) {
  const Rotor<N> r = rotor_between_frames<N>(from, to);
  CHECK((r * reverse(r) - Rotor<N>::identity()).norm() <= kTol);
  double worst = 0.0;
  for (int i = 0; i < N; ++i) worst = std::max(worst, (rotate(r, Vec<N>(from.col(i))) - to.col(i)).norm());
  CHECK(worst <= kTol);
  CHECK((to_matrix(r) - to * from.transpose()).cwiseAbs().maxCoeff() <= kTol);
}

}  // namespace

TEMPLATE_TEST_CASE("rotor_between_frames maps random frames onto each other", "[ga][frames]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(900 + N);
  for (int trial = 0; trial < 300; ++trial) {
    const Mat<N> a = oracle::rotation<N>(rng), b = oracle::rotation<N>(rng);  // (in this order in every compiler)
    check_maps<N>(a, b);
  }
  // The same frame: the identity (not -1, which is the same rotation but a full turn of the body).
  const Mat<N> a = oracle::rotation<N>(rng);
  CHECK((rotor_between_frames<N>(a, a) - Rotor<N>::identity()).norm() <= kTol);
}

TEMPLATE_TEST_CASE("rotor_between_frames: a turn in one plane gives the analytic simple rotor", "[ga][frames]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  for (const double angle : {1e-9, 0.3, 1.5, 3.0, M_PI - 1e-4}) {
    INFO("angle " << angle);
    // R = exp(-a/2 e01) turns e0 toward e1 by a (exp_log.hpp's convention), and is the only rotor with a
    // positive scalar part that does.
    const Rotor<N> truth = exp<N>(Bivector<N>::basis(0, 1) * (-angle / 2));
    const Rotor<N> r = rotor_between_frames<N>(Mat<N>::Identity(), to_matrix(truth));
    CHECK((r - truth).norm() <= kTol);
  }
}

TEMPLATE_TEST_CASE("rotor_between_frames: half turns and nearly half turns", "[ga][frames]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(950 + N);
  // Every sign pattern with an even number of flipped axes: each flipped pair is a half turn, so some
  // source axis meets its target exactly antiparallel. Also each tilted by 1e-9 rad, just off antiparallel.
  for (unsigned mask = 0; mask < (1u << N); ++mask) {
    if (std::popcount(mask) % 2) continue;
    Mat<N> d = Mat<N>::Identity();
    for (int i = 0; i < N; ++i)
      if (mask >> i & 1) d(i, i) = -1.0;
    const Mat<N> a = oracle::rotation<N>(rng);
    INFO("flipped axes mask " << mask);
    check_maps<N>(a, Mat<N>(a * d));
    check_maps<N>(a, Mat<N>(a * d * to_matrix(exp<N>(Bivector<N>::basis(0, N - 1) * 5e-10))));
  }
}

TEST_CASE("rotor_between_frames refuses frames that are not orthonormal or of opposite orientation", "[ga][frames]") {
  Mat<4> skewed = Mat<4>::Identity();
  skewed(0, 1) = 0.1;
  CHECK_THROWS_AS(rotor_between_frames<4>(Mat<4>::Identity(), skewed), Error);
  Mat<4> mirrored = Mat<4>::Identity();
  mirrored(3, 3) = -1.0;
  CHECK_THROWS_AS(rotor_between_frames<4>(Mat<4>::Identity(), mirrored), Error);
  CHECK_THROWS_AS(rotor_between_frames<4>(Mat<4>::Constant(NAN), Mat<4>::Identity()), Error);
}
