// The input layer (input/src/interaction.cpp) driven by scripted input frames, against what a hand must
// do: the grab point follows the hand, a throw leaves with the hand's velocity, a turned controller
// turns the body plane by plane (in the slice, and toward w in 4D mode), one haptic pulse per contact
// that a held body begins, and gravity tilted by a still phone's tilt. Tolerances are stated per case.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "test_util.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/mass.hpp"

using namespace wedge;
using namespace wedge::input;

namespace {

constexpr double kH = 1.0 / 120.0;
constexpr int kRight = 1;  // the hand these tests use (0 is the left)

template <int N>
Vec<N> at(double x, double y) {
  Vec<N> v = Vec<N>::Zero();
  v[0] = x;
  v[1] = y;
  return v;
}

template <int N>
BodyId add_cube(World<N>& world, const Vec<N>& where, double half = 0.1) {
  BodyDef<N> d;
  const Vec<N> he = Vec<N>::Constant(half);
  d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(he));
  const MassProperties<N> mp = box_mass_properties<N>(he, 500.0);
  d.mass = mp.mass;
  d.inertia = mp.inertia;
  d.position = where;
  return world.add_body(d);
}

template <int N>
BodyId add_ground(World<N>& world) {
  BodyDef<N> g;
  g.type = BodyType::Static;
  g.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(at<N>(0, 1), 0.0));
  return world.add_body(g);
}

template <int N>
World<N> make_world(double gravity) {
  WorldSettings<N> s;
  s.gravity = at<N>(0, -gravity);
  return World<N>(s);
}

// Runs `steps` steps with the right hand scripted by `hand(t)`; calls `check` after every step.
template <int N>
void run(World<N>& world, Interaction<N>& in, int first, int steps, const std::function<HandInput(double)>& hand,
         const std::function<void(int)>& check = {}) {
  for (int k = first; k < first + steps; ++k) {
    InputFrame f;
    f.t = k * kH;
    f.hands[kRight] = hand(f.t);
    in.before_step(f, kH);
    world.step(kH);
    in.after_step();
    if (check) check(k);
  }
}

HandInput hand_at(const Eigen::Vector3d& p, double squeeze, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity(),
                  bool mode4d = false) {
  HandInput h;
  h.tracked = true;
  h.position = p;
  h.orientation = q;
  h.squeeze = squeeze;
  h.mode4d = mode4d;
  return h;
}

}  // namespace

TEMPLATE_TEST_CASE("a held body follows the hand and is thrown with its velocity", "[input]", D2, D3, D4, D5) {
  constexpr int N = TestType::value;
  World<N> world = make_world<N>(9.81);
  add_ground(world);
  const BodyId cube = add_cube(world, at<N>(0, 0.1));
  Interaction<N> in(world, InteractionSettings<N>{});
  // 0-0.2 s grab at the centre; 0.2-0.5 s lift 0.3 m; 0.5-1.0 s carry 0.5 m along x (1 m/s); then still.
  auto path = [](double t) {
    const double lift = std::clamp((t - 0.2) / 0.3, 0.0, 1.0), carry = std::clamp((t - 0.5) / 0.5, 0.0, 1.0);
    return Eigen::Vector3d(0.5 * carry, 0.1 + 0.3 * lift, 0.0);
  };
  double moving = 0.0, settled = 0.0;
  int grabs = 0;
  run<N>(world, in, 0, 240, [&](double t) { return hand_at(path(t), 1.0); }, [&](int k) {
    for (const auto& e : in.events()) grabs += e.kind == InteractionEvent<N>::Kind::Grab && int(e.body.index) == 1;
    if (!in.grab(kRight)) return;
    const double gap = (world.grab_point(*in.grab(kRight)) - in.hand_point(kRight)).norm();
    const double t = (k + 1) * kH;
    if (t > 0.3 && t <= 1.0) moving = std::max(moving, gap);
    if (t > 1.5) settled = std::max(settled, gap);
  });
  CHECK(grabs == 1);
  REQUIRE(in.held(kRight));
  CHECK(*in.held(kRight) == cube);
  INFO("largest gap while moving " << moving << " m, after settling " << settled << " m");
  // While the hand moves at 1 m/s (and starts and stops): within 3 cm. Still: within 1 cm (the spring's
  // sag under gravity is g / w^2 = 3.9 mm at 8 Hz).
  CHECK(moving < 0.03);
  CHECK(settled < 0.01);
  // The body did not turn: the hand did not (5 degrees).
  CHECK(std::abs(world.body(cube).rotor.scalar()) > std::cos(2.5 * M_PI / 180));

  // Throw: sweep the hand at 2 m/s along x and open it at t = 2.5 s.
  auto sweep = [](double t) { return Eigen::Vector3d(0.5 + 2.0 * std::max(t - 2.0, 0.0), 0.4, 0.0); };
  std::optional<InteractionEvent<N>> released;
  run<N>(world, in, 240, 90, [&](double t) { return hand_at(sweep(t), t < 2.5 ? 1.0 : 0.0); }, [&](int) {
    for (const auto& e : in.events())
      if (e.kind == InteractionEvent<N>::Kind::Release) released = e;
  });
  REQUIRE(released);
  CHECK_FALSE(in.held(kRight));
  INFO("release velocity " << released->velocity.transpose());
  CHECK(released->velocity[0] == Approx(2.0).margin(0.1));  // the hand's velocity (5%)
  CHECK(std::abs(released->velocity[1]) < 0.1);
  CHECK(world.body(cube).center[0] > 1.5);  // it flew on
}

TEMPLATE_TEST_CASE("a turned controller turns the held body, plane by plane", "[input]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  // Turn the controller 90 degrees about its x, y or z axis over 1 s, hold 1 s; with 4D mode (N >= 4)
  // the same turn carries that axis toward w instead. Expected angle bivector: 90 degrees in one plane,
  // zero in all others, read from the body's rotor by the logarithm (theta = -2 log R) in 3D and 4D,
  // and from its matrix in 5D and 6D. Tolerance 0.5 degree: the drive's lag after 1 s of holding still
  // is below 1e-6 rad; the rest is the bound on the hand's rotor products' round-off, far smaller.
  for (bool mode4d : {false, true}) {
    if (mode4d && N < 4) continue;
    for (int axis = 0; axis < 3; ++axis) {
      if (N == 2 && axis < 2) continue;  // in 2D only the turn about z is in the plane
      World<N> world = make_world<N>(0.0);
      Vec<N> c = at<N>(0, 1.0);
      const BodyId cube = add_cube(world, c);
      Interaction<N> in(world, InteractionSettings<N>{});
      const Eigen::Vector3d p(0, 1.0, 0);
      run<N>(world, in, 0, 240, [&](double t) {
        const double a = 0.5 * M_PI * std::clamp(t - 0.1, 0.0, 1.0);
        return hand_at(p, 1.0, Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::Unit(axis))), mode4d);
      });
      // Expected: the turn carrying axis (axis+1)%3 toward (axis+2)%3 (right-hand rule), or axis toward w.
      const int from = mode4d ? axis : (axis + 1) % 3, to = mode4d ? N - 1 : (axis + 2) % 3;
      REQUIRE(std::max(from, to) < N);
      Mat<N> expected = Mat<N>::Identity();
      expected(from, from) = expected(to, to) = 0.0;
      expected(to, from) = 1.0;   // e_from -> e_to
      expected(from, to) = -1.0;  // e_to -> -e_from
      const Mat<N> got = to_matrix(world.body(cube).rotor);
      INFO("N = " << N << ", 4D mode " << mode4d << ", axis " << axis << ":\n" << got);
      CHECK((got - expected).cwiseAbs().maxCoeff() < std::sin(0.5 * M_PI / 180));
      if constexpr (N <= 4) {
        const Bivector<N> theta = log<N>(world.body(cube).rotor) * -2.0;
        for (int i = 0; i < N; ++i)
          for (int j = i + 1; j < N; ++j) {
            const double want = (i == std::min(from, to) && j == std::max(from, to)) ? (from < to ? 1 : -1) * M_PI / 2 : 0.0;
            CHECK(theta(i, j) == Approx(want).margin(0.5 * M_PI / 180));
          }
      }
      CHECK((world.body(cube).center - c).norm() < 1e-3);  // held at its centre: it turned in place
    }
  }
}

TEMPLATE_TEST_CASE("one haptic pulse per contact a held body begins, rising with the approach speed", "[input]", D3,
                   D4) {
  constexpr int N = TestType::value;
  // Lower a held cube onto the ground at `speed`, and hold it there; drop a free cube nearby.
  auto session = [](double speed, int& pulses, double& amplitude, int& pulse_step, int& begin_step, int& free_pulses) {
    World<N> world = make_world<N>(9.81);
    const BodyId ground = add_ground(world);
    const BodyId held = add_cube(world, at<N>(0, 0.6));
    const BodyId loose = add_cube(world, at<N>(1.0, 0.5));
    Interaction<N> in(world, InteractionSettings<N>{});
    pulses = free_pulses = 0;
    pulse_step = begin_step = -1;
    run<N>(world, in, 0, 360, [&](double t) {
      const double y = std::max(0.6 - speed * std::max(t - 0.1, 0.0), 0.05);  // (5 cm below the rest height)
      return hand_at(Eigen::Vector3d(0, y, 0), 1.0);
    }, [&](int k) {
      for (const auto& e : world.contact_begin_events())
        if ((e.a == ground && e.b == held) && begin_step < 0) begin_step = k;
      for (const auto& p : in.pulses()) {
        CHECK(p.hand == kRight);
        if (p.held == held && p.other == ground) {
          ++pulses;
          amplitude = p.amplitude;
          pulse_step = int(p.step);
        } else {
          ++free_pulses;
        }
        CHECK(p.duration == Approx(0.03));
        CHECK(p.frequency == 0.0);
      }
    });
    CHECK(world.body(loose).center[1] < 0.11);  // the loose cube landed (a begin event nobody holds)
  };
  int pulses = 0, pulse_step = 0, begin_step = 0, free_pulses = 0;
  double slow = 0.0, fast = 0.0;
  session(0.3, pulses, slow, pulse_step, begin_step, free_pulses);
  CHECK(pulses == 1);
  CHECK(free_pulses == 0);
  CHECK(pulse_step == begin_step);
  session(1.5, pulses, fast, pulse_step, begin_step, free_pulses);
  CHECK(pulses == 1);
  CHECK(pulse_step == begin_step);
  INFO("amplitudes: slow " << slow << ", fast " << fast);
  CHECK(fast > slow + 0.2);  // 1.5 m/s vs 0.3 m/s at 2 m/s full scale: 0.1 + 0.9 * (0.75 - 0.15) apart
  CHECK(pulse_amplitude(0.0, 2.0, 0.1) == 0.1);
  CHECK(pulse_amplitude(1.0, 2.0, 0.1) == Approx(0.55));
  CHECK(pulse_amplitude(5.0, 2.0, 0.1) == 1.0);
}

TEMPLATE_TEST_CASE("a body held from the start while resting on the ground has hit nothing until it is set down",
                   "[input]", D3, D4) {
  constexpr int N = TestType::value;
  // The world's first step reports the resting contact as beginning; that is no hit. Lifted 20 cm and set
  // down again at 0.5 m/s, the cube hits the ground once.
  World<N> world = make_world<N>(9.81);
  const BodyId ground = add_ground(world);
  const BodyId held = add_cube(world, at<N>(0, 0.1));
  Interaction<N> in(world, InteractionSettings<N>{});
  std::vector<std::int64_t> pulse_steps, begin_steps;
  run<N>(world, in, 0, 240, [&](double t) {
    const double lift = t < 0.4 ? 0.5 * t : std::max(0.2 - 0.5 * (t - 0.8), -0.05);  // up, wait, down (5 cm into it)
    return hand_at(Eigen::Vector3d(0, 0.1 + std::min(lift, 0.2), 0), 1.0);
  }, [&](int k) {
    for (const auto& e : world.contact_begin_events())
      if (e.a == ground && e.b == held) begin_steps.push_back(k);
    for (const auto& p : in.pulses()) pulse_steps.push_back(p.step);
  });
  REQUIRE(begin_steps.size() == 2);
  CHECK(begin_steps[0] == 0);            // the resting contact, reported by the first step
  CHECK(pulse_steps == std::vector<std::int64_t>{begin_steps[1]});  // only the touchdown is felt
  CHECK(in.held(kRight).has_value());
}

TEST_CASE("a still phone tilted by a known angle tilts gravity by that angle, and the tilt leaves the slice",
          "[input][gravity]") {
  for (double tilt_deg : {0.0, 10.0, 35.0}) {
    for (bool tilt_on : {false, true}) {
      World<4> world = make_world<4>(9.81);
      Interaction<4> in(world, InteractionSettings<4>{});
      // A phone upright, turned by the angle about its z axis (out of the screen): the accelerometer,
      // still, reads gravity in the device frame: (sin a, -cos a, 0) g.
      const double a = tilt_deg * M_PI / 180;
      std::vector<input::MotionSample> samples;
      for (int i = 0; i <= 300; ++i) {  // 3 s at 100 Hz
        input::MotionSample m;
        m.t = i * 0.01;
        m.acceleration = Eigen::Vector3d(std::sin(a), -std::cos(a), 0.0);
        m.tilt = tilt_on;
        samples.push_back(m);
      }
      std::size_t used = 0;
      for (int k = 0; k <= 360; ++k) {
        InputFrame f;
        f.t = k * kH;
        std::size_t end = used;
        while (end < samples.size() && samples[end].t <= f.t) ++end;
        f.motion = std::span<const input::MotionSample>(samples.data() + used, end - used);
        used = end;
        in.before_step(f, kH);
        world.step(kH);
      }
      const Vec<4> g = world.gravity();
      CHECK(g.norm() == Approx(9.81).epsilon(1e-12));  // the scene's magnitude
      const Eigen::Vector3d in_slice = g.head<3>();
      const double out_of_slice = std::atan2(g[3], in_slice.norm()) * 180 / M_PI;
      const double turned = std::atan2(in_slice[0], -in_slice[1]) * 180 / M_PI;
      INFO("tilt " << tilt_deg << ", tilt on " << tilt_on << ": in-slice angle " << turned << ", out " << out_of_slice);
      // The device's tilt comes through exactly (a constant input through a linear filter).
      CHECK(turned == Approx(tilt_deg).margin(1e-9));
      CHECK(out_of_slice == Approx(tilt_on ? 15.0 : 0.0).margin(1e-9));
    }
  }
  World<3> w3 = make_world<3>(9.81);
  InteractionSettings<3> s3;
  s3.gravity_tilt_on = true;
  CHECK_THROWS_WITH((Interaction<3>(w3, s3)), Catch::Contains("w axis"));
}

TEST_CASE("moving the tracking origin along w carries a held body into w, with no jolt from the move", "[input]") {
  // The hands follow the slice (wedge xr's thumbstick): a body held at w = 0 when the origin moves 0.3 m
  // along w is pulled there by its grab spring. The move is not a hand motion: had it been taken for one,
  // the hand's velocity for that step (0.3 m / h = 36 m/s) would fling the body. A critically damped
  // spring of angular frequency omega released from rest Delta away peaks at Delta omega / e = 5.5 m/s
  // here (omega = 2 pi 8 Hz), less under the acceleration limit: the bound is 6 m/s.
  World<4> world = make_world<4>(0.0);
  const BodyId cube = add_cube(world, at<4>(0, 1.0));
  InteractionSettings<4> s;
  Interaction<4> in(world, s);
  double peak = 0.0;
  for (int k = 0; k < 300; ++k) {
    if (k == 60) {
      Vec<4> origin = Vec<4>::Zero();
      origin[3] = 0.3;
      in.set_tracking_origin(origin);
    }
    InputFrame f;
    f.t = k * kH;
    f.hands[kRight] = hand_at(Eigen::Vector3d(0, 1.0, 0), 1.0);
    in.before_step(f, kH);
    world.step(kH);
    in.after_step();
    peak = std::max(peak, world.body(cube).velocity.norm());
  }
  CHECK(in.held(kRight) == cube);
  CHECK(in.hand_point(kRight)[3] == 0.3);
  CHECK(world.body(cube).center[3] == Approx(0.3).margin(1e-3));
  CHECK(std::abs(world.body(cube).center[1] - 1.0) < 1e-3);
  INFO("peak speed " << peak << " m/s");
  CHECK(peak < 6.0);
  CHECK(peak > 0.5);  // (it did move)
}
