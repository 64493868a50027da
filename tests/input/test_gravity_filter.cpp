// The gravity filter (input/gravity_filter.hpp) against truth:
//   - a device spinning at a constant rate, with an accelerometer that reads exactly the turning gravity:
//     the estimate follows to round-off, which pins the gyro's sign and its exact integration;
//   - a still device and a wrong first estimate: the error decays exactly as the discretised first-order
//     system g_n = g + (g_0 - g) exp(-t_n / tau);
//   - a real hand-held iPhone (recordings/coremotion/kinetic_tremor_data.csv, 9.4 s at ~93 Hz, tremor
//     and a tilt of up to 24 degrees) against CoreMotion's own fused gravity, which is Apple's estimate,
//     not ground truth: measured 4.0 degrees at the median and 8.0 at p95 (tau = 5 s, after 1 s);
//     asserted below 5 and 9 degrees. The accelerometer alone, low-passed, is 15 degrees off: checked too,
//     so the test shows what the gyro buys.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "wedge/error.hpp"
#include "wedge/input/gravity_filter.hpp"
#include "wedge/recordings/coremotion_csv.hpp"

using wedge::input::GravityFilter;
using wedge::input::GravityFilterSettings;

namespace {

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

// Median and 95th percentile of the angle between the filter's direction and CoreMotion's gravity, after
// the first second.
std::pair<double, double> replay_errors(double tau, bool use_gyro) {
  const auto samples = wedge::recordings::read_coremotion_csv(std::string(WEDGE_SOURCE_DIR) +
                                                              "/recordings/coremotion/kinetic_tremor_data.csv");
  GravityFilter f(GravityFilterSettings{tau});
  std::vector<double> errors;
  double last = samples.front().time;
  for (const auto& s : samples) {
    f.update(s.user_acceleration + s.gravity, use_gyro ? s.rotation_rate : Eigen::Vector3d::Zero(), s.time - last);
    last = s.time;
    if (s.time > 1.0) errors.push_back(angle_deg(f.direction(), s.gravity));
  }
  std::sort(errors.begin(), errors.end());
  return {errors[errors.size() / 2], errors[std::size_t(0.95 * double(errors.size()))]};
}

}  // namespace

TEST_CASE("gravity filter: a spinning device with an exact accelerometer is followed to round-off",
          "[input][gravity]") {
  const Eigen::Vector3d w(0.3, -1.1, 0.7), g0(0.2, -0.9, -0.38);
  const double dt = 0.01;
  GravityFilter f(GravityFilterSettings{0.5});
  double worst = 0.0;
  for (int n = 0; n <= 1000; ++n) {
    // Gravity seen from the device after n steps: turned by -|w| n dt about w.
    const Eigen::Vector3d g = Eigen::AngleAxisd(-w.norm() * n * dt, w.normalized()) * g0;
    f.update(g, w, n == 0 ? 0.0 : dt);
    worst = std::max(worst, (f.gravity() - g).norm());
  }
  CHECK(worst < 1e-12);  // 1000 exact rotations: round-off only
  // With the gyro's sign reversed, the same run drifts away by the full turn's error: the sign matters.
  GravityFilter wrong(GravityFilterSettings{0.5});
  double off = 0.0;
  for (int n = 0; n <= 100; ++n) {
    const Eigen::Vector3d g = Eigen::AngleAxisd(-w.norm() * n * dt, w.normalized()) * g0;
    wrong.update(g, -w, n == 0 ? 0.0 : dt);
    off = std::max(off, angle_deg(wrong.gravity(), g));
  }
  CHECK(off > 1.0);
}

TEST_CASE("gravity filter: a wrong start decays as the first-order system exp(-t/tau)", "[input][gravity]") {
  const Eigen::Vector3d g(0, 0, -1), start(0.5, 0, -0.866);
  const double tau = 2.0, dt = 0.01;
  GravityFilter f(GravityFilterSettings{tau});
  f.update(start, Eigen::Vector3d::Zero(), 0.0);
  for (int n = 1; n <= 600; ++n) {
    f.update(g, Eigen::Vector3d::Zero(), dt);
    const Eigen::Vector3d truth = g + (start - g) * std::exp(-n * dt / tau);
    REQUIRE((f.gravity() - truth).norm() < 1e-12);
  }
}

TEST_CASE("gravity filter: a real hand-held iPhone against CoreMotion's fused gravity",
          "[input][gravity][recordings]") {
  const auto [median, p95] = replay_errors(5.0, true);
  INFO("median " << median << " deg, p95 " << p95 << " deg");
  CHECK(median < 5.0);
  CHECK(p95 < 9.0);
  // What the gyro buys: the accelerometer alone, low-passed at any time constant, is far worse.
  for (const double tau : {0.1, 0.5, 5.0}) {
    const auto [accel_median, accel_p95] = replay_errors(tau, false);
    INFO("accelerometer only, tau " << tau << ": median " << accel_median << " deg");
    CHECK(accel_median > 2 * median);
  }
}

TEST_CASE("gravity filter: bad settings and samples are refused", "[input][gravity]") {
  CHECK_THROWS_AS(GravityFilter(GravityFilterSettings{0.0}), wedge::Error);
  CHECK_THROWS_AS(GravityFilter(GravityFilterSettings{INFINITY}), wedge::Error);
  GravityFilter f;
  CHECK(!f.ready());
  CHECK(f.direction() == Eigen::Vector3d::Zero());
  CHECK_THROWS_AS(f.update(Eigen::Vector3d(0, NAN, 0), Eigen::Vector3d::Zero(), 0.01), wedge::Error);
  CHECK_THROWS_AS(f.update(Eigen::Vector3d(0, -1, 0), Eigen::Vector3d::Zero(), -0.01), wedge::Error);
  f.update(Eigen::Vector3d(0, -2, 0), Eigen::Vector3d::Zero(), 0.0);
  CHECK(f.ready());
  CHECK(f.direction() == Eigen::Vector3d(0, -1, 0));
}
