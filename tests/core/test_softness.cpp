// make_softness (wedge/softness.hpp) against the implicit Euler step of a damped spring, solved by hand:
// for a unit mass with x'' = -w^2 x - 2 z w x', implicit Euler gives
//   v1 = v0 + h (-w^2 x1 - 2 z w v1),  x1 = x0 + h v1   =>   v1 = (v0 - h w^2 x0) / (1 + 2 z w h + w^2 h^2).
// The soft constraint's velocity update from rest of the accumulated impulse, v1 = v0 - mass_scale (v0 +
// bias_rate x0), must be that same v1 for every frequency, damping ratio and step. Both sides are a few
// products of numbers of order 1..1e3, so they agree to round-off: 1e-13 relative.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "wedge/softness.hpp"

TEST_CASE("softness: one soft step is implicit Euler on the damped spring", "[softness]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> frequency(0.1, 120.0), damping(0.0, 5.0), step(1e-4, 0.05),
      value(-3.0, 3.0);
  for (int i = 0; i < 1000; ++i) {
    const double f = frequency(rng), z = damping(rng), h = step(rng), x0 = value(rng), v0 = value(rng);
    const double w = 2.0 * std::numbers::pi * f;
    const double expected = (v0 - h * w * w * x0) / (1.0 + 2.0 * z * w * h + w * w * h * h);
    const wedge::Softness s = wedge::make_softness(f, z, h);
    const double v1 = v0 - s.mass_scale * (v0 + s.bias_rate * x0);
    INFO("f " << f << " z " << z << " h " << h);
    CHECK(std::abs(v1 - expected) <= 1e-13 * (std::abs(v0) + h * w * w * std::abs(x0)));
    // The accumulated impulse relaxes by the share the rigid answer does not take: the two add up to 1
    // (to a few ulps of 1: 1 - mass_scale cancels when the spring is stiff).
    CHECK(std::abs(s.impulse_scale + s.mass_scale - 1.0) <= 1e-15);
  }
}

TEST_CASE("softness: a stiff spring tends to the rigid constraint, frequency 0 is rigid", "[softness]") {
  const wedge::Softness rigid = wedge::make_softness(0.0, 1.0, 1.0 / 60.0);
  CHECK(rigid.bias_rate == 0.0);
  CHECK(rigid.mass_scale == 1.0);
  CHECK(rigid.impulse_scale == 0.0);
  // At f -> infinity the step removes all the velocity error and asks for the whole position error in one
  // step: mass_scale -> 1, bias_rate -> 1 / h.
  const double h = 1.0 / 60.0;
  const wedge::Softness stiff = wedge::make_softness(1e6, 1.0, h);
  CHECK(stiff.mass_scale == Approx(1.0).epsilon(1e-9));
  CHECK(stiff.bias_rate * h == Approx(1.0).epsilon(1e-4));
}

TEST_CASE("softness: repeated soft steps decay a critically damped spring without overshoot", "[softness]") {
  // Implicit Euler on a critically damped spring never crosses zero from x0 > 0, v0 = 0, at any step:
  // the discrete system's eigenvalues are real and positive. 30 Hz at a 1/60 s step is far past what an
  // explicit step could hold (w h = 3.1).
  const double f = 30.0, h = 1.0 / 60.0;
  const wedge::Softness s = wedge::make_softness(f, 1.0, h);
  double x = 1.0, v = 0.0;
  for (int i = 0; i < 200; ++i) {
    v = v - s.mass_scale * (v + s.bias_rate * x);
    x += h * v;
    REQUIRE(x >= 0.0);
  }
  CHECK(x < 1e-12);
}
