// Joints (wedge/joint.hpp, core/src/contact/joints.cpp) against what mechanics says they must do, 2D-6D:
//   - a bob on a rod (distance joint to the world) swings with the simple pendulum's period: 2 pi sqrt(L/g)
//     at small amplitude, 4 sqrt(L/g) K(sin(theta0/2)) at 90 degrees (complete elliptic integral K), each
//     to 0.5%, and stays in its plane;
//   - a bar on a point joint at its end swings with the physical pendulum's period 2 pi sqrt(I_p/(m g d)),
//     I_p from the bar's dimensions (m (a^2 + b^2)/3 about the centre, plus m d^2);
//   - a 20-link chain dropped from horizontal hangs with every joint gap under 1 mm; with a 100:1 mass at
//     its end it still holds together (the gap stated below);
//   - a rope (distance joint with a maximum length) lets its body fall freely until taut, then holds it;
//     a spring's body oscillates at the spring's frequency and rests at the static deflection g/w^2;
//   - joints are internal forces: two joined bodies keep their linear momentum to round-off;
//   - joined bodies do not collide unless asked; the paper's solver and bad definitions are refused;
//     ids are checked; a removed joint lets go;
//   - a double pendulum keeps its energy; a revolute joint turns only in its plane, drives with its motor
//     and stops at its limits; a weld holds a cantilever, a soft one with the sag its springs predict;
//   - a prismatic slider slides at g cos(angle) and never turns, turns its two bodies together, drives
//     with its motor within its force and stops at its limits.
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "test_util.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

constexpr double kG = 9.81;

template <int N>
Vec<N> xy(double x, double y) {
  Vec<N> v = Vec<N>::Zero();
  v[0] = x;
  v[1] = y;
  return v;
}

template <int N>
World<N> pendulum_world() {
  WorldSettings<N> s;
  s.gravity = xy<N>(0.0, -kG);
  s.contact.allow_sleep = false;  // (a pendulum at the end of its swing is briefly slow)
  return World<N>(s);
}

template <int N>
BodyDef<N> placed(const Shape<N>& shape, double density, const Vec<N>& at) {
  BodyDef<N> d = body_def<N>(std::make_shared<const Shape<N>>(shape), density);
  d.position = at;
  return d;
}

template <int N>
BodyDef<N> ball(double radius, const Vec<N>& at) {
  return placed<N>(Shape<N>::ball(radius), 1000.0, at);
}

template <int N>
BodyDef<N> box(const Vec<N>& half, double density, const Vec<N>& at) {
  return placed<N>(Shape<N>::box(half), density, at);
}

// The period of x(t) of the body's centre, from its downward zero crossings (linear interpolation
// between steps), over `duration` seconds; also the largest |coordinate| outside the x-y plane seen.
struct Swing {
  double period = 0.0;
  int crossings = 0;
  double off_plane = 0.0;  // m
  double last_amplitude = 0.0;  // m, the largest |x| in the last period
};

template <int N>
Swing swing(World<N>& world, BodyId bob, double h, double duration) {
  Swing out;
  std::vector<double> down;
  double x_prev = world.body(bob).center[0];
  std::vector<std::pair<double, double>> xs;
  for (int i = 1; i * h <= duration + 1e-9; ++i) {
    world.step(h);
    const Vec<N>& c = world.body(bob).center;
    for (int k = 2; k < N; ++k) out.off_plane = std::max(out.off_plane, std::abs(c[k]));
    const double x = c[0];
    if (x_prev > 0.0 && x <= 0.0) down.push_back((i - 1) * h + h * x_prev / (x_prev - x));
    xs.emplace_back(i * h, x);
    x_prev = x;
  }
  out.crossings = int(down.size());
  if (down.size() >= 2) out.period = (down.back() - down.front()) / double(down.size() - 1);
  for (const auto& [t, x] : xs)
    if (t > duration - out.period) out.last_amplitude = std::max(out.last_amplitude, std::abs(x));
  return out;
}

}  // namespace

TEMPLATE_TEST_CASE("joints: a bob on a rod swings with the simple pendulum's period", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double L = 1.0, h = 1.0 / 60.0;
  for (const double theta0 : {0.05, M_PI / 2}) {
    CAPTURE(theta0);
    World<N> world = pendulum_world<N>();
    const BodyId bob = world.add_body(ball<N>(0.05, xy<N>(L * std::sin(theta0), -L * std::cos(theta0))));
    DistanceJointDef<N> rod;
    rod.body_b = bob;  // (body_a: the world; anchor_a the pivot at the origin; anchor_b the bob's centre)
    const JointId joint = world.add_joint(rod);
    REQUIRE(world.joint_type(joint) == JointType::Distance);
    // The rod acts through the bob's centre, so the bob does not turn: a point mass on a massless rod.
    // Period of the simple pendulum, exact for any amplitude: T = 4 sqrt(L/g) K(k), k = sin(theta0/2).
    const double exact = 4.0 * std::sqrt(L / kG) * std::comp_ellint_1(std::sin(theta0 / 2));
    const double e0 = world.kinetic_energy() + world.potential_energy();
    const Swing s = swing(world, bob, h, 12.0);
    const double e1 = world.kinetic_energy() + world.potential_energy();
    INFO("period " << s.period << " s (exact " << exact << "), energy " << e0 << " -> " << e1 << " J, amplitude "
                   << s.last_amplitude << " m");
    REQUIRE(s.crossings >= 5);
    CHECK(s.period == Approx(exact).epsilon(0.005));
    if (theta0 < 0.1) CHECK(s.period == Approx(2 * M_PI * std::sqrt(L / kG)).epsilon(0.005));
    // Gravity, the rod and the start all lie in the x-y plane: nothing leaves it.
    CHECK(s.off_plane == 0.0);
    // The rod's length is held: within 1 mm through the swing.
    CHECK(std::abs((world.joint_anchor_b(joint) - world.joint_anchor_a(joint)).norm() - L) < 1e-3);
    // Energy: the soft step's implicit springs damp the swing a little; over 12 s the amplitude keeps
    // 99% of its start (the measured loss is printed by the period test's figures in docs/joints.md).
    CHECK(s.last_amplitude > 0.99 * L * std::sin(theta0));
    // The rod pulls the bob toward the pivot with the centripetal force plus gravity's share: at rest
    // the tension would be m g; here it is finite and points along the rod.
    const Vec<N> f = world.joint_force(joint);
    const Vec<N> to_pivot = -world.body(bob).center.normalized();
    CHECK(f.normalized().dot(to_pivot) == Approx(1.0).margin(1e-6));
  }
}

TEMPLATE_TEST_CASE("joints: a bar on a point joint swings with the physical pendulum's period", "[joints]", D2, D3, D4,
                   D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0, theta0 = 0.05;
  const double a = 0.05, b = 0.4;  // m, half extents across and along the bar; the joint at one end
  World<N> world = pendulum_world<N>();
  Vec<N> half = Vec<N>::Constant(0.05);
  half[0] = a;
  half[1] = b;
  // The bar hangs from the pivot at the origin, its centre d = b below it, turned by theta0 in the x-y plane.
  BodyDef<N> def = box<N>(half, 500.0, xy<N>(b * std::sin(theta0), -b * std::cos(theta0)));
  Mat<N> turn = Mat<N>::Identity();  // counter-clockwise by theta0 in the x-y plane: the bar's top to the pivot
  turn(0, 0) = turn(1, 1) = std::cos(theta0);
  turn(0, 1) = -std::sin(theta0);
  turn(1, 0) = std::sin(theta0);
  def.rotor = rotor_from_matrix<N>(turn);
  const BodyId bar = world.add_body(def);
  PointJointDef<N> pin;
  pin.body_b = bar;
  pin.anchor_b = xy<N>(0.0, b);  // the bar's top end, in its frame
  const JointId joint = world.add_joint(pin);
  REQUIRE((world.joint_anchor_b(joint) - world.joint_anchor_a(joint)).norm() < 1e-12);
  // A box's inertia about its centre for a turn in the x-y plane: m ((2a)^2 + (2b)^2) / 12; about the
  // pivot, plus m d^2 (parallel axis). Small-angle period 2 pi sqrt(I_p / (m g d)), and the finite
  // amplitude raises it by the factor K(sin(theta0/2)) 2/pi (1.00016 here).
  const double m = world.body(bar).mass;
  const double ip = m * (a * a + b * b) / 3.0 + m * b * b;
  const double t0 = 2 * M_PI * std::sqrt(ip / (m * kG * b));
  const double exact = t0 * std::comp_ellint_1(std::sin(theta0 / 2)) * 2 / M_PI;
  const Swing s = swing(world, bar, h, 10.0);
  REQUIRE(s.crossings >= 4);
  CHECK(s.period == Approx(exact).epsilon(0.005));
  CHECK(s.off_plane == 0.0);
  // The pin holds: the two anchors stay within 0.1 mm.
  CHECK((world.joint_anchor_b(joint) - world.joint_anchor_a(joint)).norm() < 1e-4);
}

namespace {

// A chain of `links` bars of length 2 * half_length along x (or, `down`, along -y), the first pinned to the world at the
// origin, each pinned to the next at their shared end; the last link's mass is `end_mass_ratio` times a
// link's. Returns the joints.
template <int N>
std::vector<JointId> chain(World<N>& world, int links, double half_length, double end_mass_ratio, bool down) {
  std::vector<JointId> joints;
  Vec<N> half = Vec<N>::Constant(0.02);
  half[0] = half_length;
  Mat<N> quarter = Mat<N>::Identity();  // x to -y: the links' long axis straight down
  quarter(0, 0) = quarter(1, 1) = 0.0;
  quarter(1, 0) = -1.0;
  quarter(0, 1) = 1.0;
  std::optional<BodyId> previous;
  for (int i = 0; i < links; ++i) {
    const double density = i == links - 1 ? 300.0 * end_mass_ratio : 300.0;
    const double along = (2 * i + 1) * half_length;
    BodyDef<N> def = box<N>(half, density, down ? xy<N>(0.0, -along) : xy<N>(along, 0.0));
    if (down) def.rotor = rotor_from_matrix<N>(quarter);
    const BodyId link = world.add_body(def);
    PointJointDef<N> pin;
    pin.body_a = previous;
    pin.anchor_a = previous ? xy<N>(half_length, 0.0) : Vec<N>(Vec<N>::Zero());
    pin.body_b = link;
    pin.anchor_b = xy<N>(-half_length, 0.0);
    joints.push_back(world.add_joint(pin));
    previous = link;
  }
  return joints;
}

template <int N>
double largest_gap(const World<N>& world, const std::vector<JointId>& joints) {
  double gap = 0.0;
  for (const JointId j : joints) gap = std::max(gap, (world.joint_anchor_b(j) - world.joint_anchor_a(j)).norm());
  return gap;
}

}  // namespace

TEMPLATE_TEST_CASE("joints: a 20-link chain hangs together, and holds a 100:1 mass", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0;
  for (const double ratio : {1.0, 100.0}) {
    CAPTURE(ratio);
    WorldSettings<N> s;
    s.gravity = xy<N>(0.0, -kG);
    // Hanging: the chain built straight down (the links turned a quarter turn), left for 5 s.
    World<N> hanging(s);
    const std::vector<JointId> held = chain(hanging, 20, 0.05, ratio, true);
    for (int i = 0; i < 300; ++i) hanging.step(h);
    const double rest_gap = largest_gap(hanging, held);
    // Dropped from horizontal: 10 s of falling and swinging.
    World<N> dropped(s);
    const std::vector<JointId> joints = chain(dropped, 20, 0.05, ratio, false);
    double swinging = 0.0;
    for (int i = 0; i < 600; ++i) {
      dropped.step(h);
      swinging = std::max(swinging, largest_gap(dropped, joints));
    }
    INFO("largest gap hanging " << rest_gap * 1e3 << " mm, while swinging " << swinging * 1e3 << " mm");
    // Each pin carries the links below it (and the end mass); the soft step's joints hold a hanging
    // chain within 1 mm at every pin, and the swinging one within a centimetre (the end mass: 5 cm).
    CHECK(rest_gap < (ratio > 1.0 ? 5e-3 : 1e-3));
    CHECK(swinging < (ratio > 1.0 ? 0.05 : 0.01));
    // Hanging: the end is 1.95 m below the pivot plus every pin's stretch. A joint is a spring of
    // stiffness m_eff w^2 (w = 2 pi min(joint_hertz, a quarter of the sub-step rate)), m_eff its
    // effective mass along the chain, 1/(1/m_i + 1/m_(i+1)) between links (the lever arms lie along
    // the load, so the bodies' inertias do not enter) and m_1 at the pivot; it carries the weight of
    // the links below it. The sum of those static deflections predicts the end to 1% of the stretch.
    // With the 100:1 end mass the chain rests 7% longer than that (one pass per sub-step: each pin is
    // solved seeing the velocity its lower neighbour has before that neighbour's pin is), so 10% there.
    const double link = hanging.body(BodyId{0}).mass, last = hanging.body(BodyId{19}).mass;
    const double w = 2 * M_PI * std::min(s.contact.joint_hertz, 0.25 * s.contact.substeps / h);
    double stretch = 0.0;
    for (int i = 0; i < 20; ++i) {  // pin i holds link i (and everything below) to link i - 1 or the world
      const double load = (19 - i) * link + last;
      const double m_eff = i == 0 ? link : 1.0 / (1.0 / link + 1.0 / (i == 19 ? last : link));
      stretch += load * kG / (m_eff * w * w);
    }
    const Vec<N>& end = hanging.body(BodyId{19}).center;
    INFO("end " << end[1] << " m, predicted " << -1.95 - stretch << " m");
    CHECK(end[1] == Approx(-1.95 - stretch).margin((ratio > 1.0 ? 0.1 : 0.01) * stretch));
    for (int k = 2; k < N; ++k) CHECK(end[k] == 0.0);
  }
}

TEMPLATE_TEST_CASE("joints: a rope lets its body fall freely until taut, then holds it", "[joints]", D2, D3, D4) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0;
  World<N> world = pendulum_world<N>();
  const BodyId bob = world.add_body(ball<N>(0.05, xy<N>(0.0, -0.2)));
  DistanceJointDef<N> rope;
  rope.body_b = bob;
  rope.spring = true;  // (frequency 0: no spring force; only the limits act: a rope)
  rope.min_length = 0.0;
  rope.max_length = 1.0;
  rope.length = 0.5;
  const JointId joint = world.add_joint(rope);
  // Slack: free fall. It reaches the rope's end (0.8 m down) at t = sqrt(2 * 0.8 / g) = 0.404 s. The
  // sub-steps (h_s = h / 8) are symplectic Euler, velocity first: after n of them y = y0 - g h_s^2 n (n + 1) / 2
  // = y0 - g t (t + h_s) / 2 exactly.
  for (int i = 0; i < 36; ++i) world.step(h);  // 0.3 s
  const double t = 0.3, hs = h / 8;
  CHECK(world.body(bob).center[1] == Approx(-0.2 - 0.5 * kG * t * (t + hs)).epsilon(1e-9));
  CHECK(world.body(bob).velocity[1] == Approx(-kG * 0.3).epsilon(1e-9));
  for (int i = 0; i < 360; ++i) world.step(h);
  // Taut: it hangs at the rope's length within 1 mm, at rest (the rope took the fall's speed at once: a
  // rigid limit, restitution 0), and the rope carries the weight.
  CHECK(world.body(bob).center[1] == Approx(-1.0).margin(1e-3));
  CHECK(world.body(bob).velocity.norm() < 1e-3);
  CHECK(world.joint_force(joint)[1] == Approx(world.body(bob).mass * kG).epsilon(1e-3));
}

TEMPLATE_TEST_CASE("joints: a spring oscillates at its frequency and rests at g / w^2", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0, f = 2.0, w = 2 * M_PI * f, rest = 0.5;
  for (const double zeta : {0.0, 1.0}) {
    CAPTURE(zeta);
    World<N> world = pendulum_world<N>();
    const BodyId bob = world.add_body(ball<N>(0.05, xy<N>(0.0, -rest)));
    DistanceJointDef<N> spring;
    spring.body_b = bob;
    spring.spring = true;
    spring.length = rest;
    spring.frequency = f;
    spring.damping_ratio = zeta;
    world.add_joint(spring);
    if (zeta == 0.0) {
      // Undamped: released at the rest length, the bob oscillates about rest + g/w^2 with period 1/f.
      // Implicit Euler on the spring (the soft constraint) lengthens the period by O((h w)^2) per
      // sub-step: well under 0.5% at 960 sub-steps a second.
      double low = 0.0, first_low = 0.0;
      int turns = 0;
      double first = 0.0, last = 0.0;
      double v_prev = 0.0;
      for (int i = 1; i <= 600; ++i) {
        world.step(h);
        const double v = world.body(bob).velocity[1];
        if (v_prev < 0.0 && v >= 0.0) {  // lowest point
          const double t = (i - 1) * h + h * (-v_prev) / (v - v_prev);
          if (turns == 0) {
            first = t;
            first_low = world.body(bob).center[1];
          }
          last = t;
          ++turns;
          low = world.body(bob).center[1];
        }
        v_prev = v;
      }
      REQUIRE(turns >= 5);
      CHECK((last - first) / (turns - 1) == Approx(1.0 / f).epsilon(0.005));
      // The first swing reaches 2 g/w^2 below the rest length. Implicit Euler damps an undamped spring:
      // the amplitude falls by a factor 1/sqrt(1 + (h_s w)^2) per sub-step, 0.66 over 5 s here
      // (h_s w = 0.013), so the last swing is checked against that.
      // The first swing reaches 2 g/w^2 below the rest length, less what implicit Euler takes: an
      // undamped spring's amplitude falls by 1/sqrt(1 + (h_s w)^2) per sub-step (h_s w = 0.013, 2% by the
      // first low point).
      const double hs = h / 8, damped = std::pow(1.0 + hs * w * hs * w, -0.5 * first / hs);
      INFO("first swing " << -first_low - rest << " m, last " << -low - rest << " m");
      CHECK(-first_low - rest == Approx(2 * kG / (w * w) * damped).epsilon(0.005));
      CHECK(-low - rest > 0.5 * 2 * kG / (w * w));
    } else {
      for (int i = 0; i < 600; ++i) world.step(h);
      // Critically damped, 5 s (60 time constants): at rest at the static deflection, to 1e-6 m.
      CHECK(world.body(bob).center[1] == Approx(-rest - kG / (w * w)).margin(1e-6));
    }
  }
}

TEMPLATE_TEST_CASE("joints: two joined bodies keep their linear momentum", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  World<N> world;  // no gravity
  Vec<N> half = Vec<N>::Constant(0.1);
  half[0] = 0.3;
  BodyDef<N> da = box<N>(half, 1000.0, xy<N>(-0.3, 0.0));
  BodyDef<N> db = box<N>(Vec<N>(Vec<N>::Constant(0.15)), 4000.0, xy<N>(0.15, 0.0));
  da.velocity = xy<N>(0.5, 1.0);
  da.angular_velocity = Bivector<N>::basis(0, 1) * 3.0;
  db.velocity = xy<N>(-1.0, 0.2);
  const BodyId a = world.add_body(da);
  const BodyId b = world.add_body(db);
  PointJointDef<N> pin;
  pin.body_a = a;
  pin.anchor_a = xy<N>(0.3, 0.0);
  pin.body_b = b;
  pin.anchor_b = xy<N>(-0.15, 0.0);
  const JointId joint = world.add_joint(pin);
  const Vec<N> p0 = world.linear_momentum();
  double gap = 0.0;
  for (int i = 0; i < 240; ++i) {
    world.step(1.0 / 120.0);
    gap = std::max(gap, (world.joint_anchor_b(joint) - world.joint_anchor_a(joint)).norm());
  }
  // Every joint impulse acts on both bodies, equal and opposite: the sum of m v changes by round-off.
  CHECK((world.linear_momentum() - p0).norm() < 1e-12 * (1.0 + p0.norm()));
  // The pin held the tumbling pair together (they started joined).
  CHECK(gap < 1e-3);
  // And no contact between the joined bodies (collide_connected false), though their boxes touch.
  CHECK(world.contacts().empty());
}

TEMPLATE_TEST_CASE("joints: joined bodies collide only when asked", "[joints]", D2, D3, D4) {
  constexpr int N = TestType::value;
  for (const bool collide : {false, true}) {
    CAPTURE(collide);
    World<N> world;
    const BodyId a = world.add_body(box<N>(Vec<N>(Vec<N>::Constant(0.2)), 1000.0, xy<N>(0.0, 0.0)));
    const BodyId b = world.add_body(box<N>(Vec<N>(Vec<N>::Constant(0.2)), 1000.0, xy<N>(0.3, 0.0)));  // overlap 0.1 m
    PointJointDef<N> pin;
    pin.body_a = a;
    pin.anchor_a = xy<N>(0.15, 0.0);
    pin.body_b = b;
    pin.anchor_b = xy<N>(-0.15, 0.0);
    pin.collide_connected = collide;
    const JointId joint = world.add_joint(pin);
    world.step(1.0 / 60.0);
    CHECK(world.contacts().empty() == !collide);
    // Removing the joint lets them collide (and push apart).
    world.remove_joint(joint);
    world.step(1.0 / 60.0);
    CHECK_FALSE(world.contacts().empty());
  }
}

TEST_CASE("joints: bad definitions, the paper's solver and stale ids are refused", "[joints]") {
  WorldSettings<3> s;
  World<3> world(s);
  const BodyId ground = world.add_body([] {
    BodyDef<3> d;
    d.type = BodyType::Static;
    d.name = "ground";
    return d;
  }());
  const BodyId a = world.add_body(box<3>(Vec<3>::Constant(0.1), 1000.0, Vec<3>(0, 1, 0)));
  const auto refused = [&](auto def, const char* what) {
    CAPTURE(what);
    try {
      world.add_joint(def);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK_THAT(e.what(), Catch::Contains(what));
    }
  };
  PointJointDef<3> pin;
  pin.body_b = BodyId{7};
  refused(pin, "body id 7");
  pin.body_b = a;
  pin.body_a = a;
  refused(pin, "same body");
  pin.body_a = ground;
  pin.body_b = ground;
  refused(pin, "same body");
  pin.body_a.reset();
  refused(pin, "neither body is dynamic");
  pin.body_b = a;
  pin.anchor_b[0] = std::nan("");
  refused(pin, "anchors must be finite");
  DistanceJointDef<3> rod;
  rod.body_b = a;
  rod.anchor_a = Vec<3>(0, 1, 0);  // at the body's centre: length 0
  refused(rod, "length must be finite and >= 0.1 mm");
  rod.spring = true;
  rod.length = 0.5;
  rod.min_length = 0.6;
  rod.max_length = 0.4;
  refused(rod, "max_length");
  rod.max_length = 1.0;
  refused(rod, "must lie in [min_length, max_length]");
  rod.length = 0.7;
  rod.frequency = -1.0;
  refused(rod, "frequency");
  PrismaticJointDef<3> slide;
  slide.body_b = a;
  slide.axis_a = Vec<3>(1, 1, 0);
  refused(slide, "axis_a must be a unit vector");
  slide.axis_a = Vec<3>(0, 1, 0);
  slide.lower_translation = 0.5;
  slide.upper_translation = -0.5;
  refused(slide, "lower_translation and upper_translation");
  slide.upper_translation = 1.0;
  slide.max_motor_force = -1.0;
  refused(slide, "max_motor_force");
  CHECK(world.joint_count() == 0);
  slide.max_motor_force = 0.0;
  const JointId slid = world.add_joint(slide);
  CHECK(world.joint_type(slid) == JointType::Prismatic);
  CHECK(world.joint_translation(slid) == Approx(1.0));  // the body's centre, 1 m up the axis from the origin
  CHECK_THROWS_WITH(world.joint_angle(slid), Catch::Contains("not a revolute joint"));
  world.remove_joint(slid);

  pin.anchor_b.setZero();
  const JointId j = world.add_joint(pin);
  CHECK(world.has_joint(j));
  CHECK(world.joint_count() == 1);
  CHECK(world.joint_force(j) == Vec<3>::Zero());
  CHECK_THROWS_WITH(world.joint_translation(j), Catch::Contains("not a prismatic joint"));
  // The paper's solver has no joints: switching to it is refused while one lives, and so is adding one.
  CHECK_THROWS_WITH(world.update_settings([](auto& st) { st.contact.solver = ContactSolver::Paper; }),
                    Catch::Contains("paper's contact solver has no joints"));
  world.remove_joint(j);
  CHECK_FALSE(world.has_joint(j));
  CHECK_THROWS_WITH(world.joint_force(j), Catch::Contains("not a live joint"));
  CHECK_THROWS_WITH(world.remove_joint(j), Catch::Contains("not a live joint"));
  // The slot is reused with a new generation: the old id stays dead.
  const JointId again = world.add_joint(pin);
  CHECK(again.index == j.index);
  CHECK_FALSE(world.has_joint(j));
  world.remove_joint(again);
  // Freed slots are taken lowest first, whatever order they were freed in; then new slots follow.
  std::vector<JointId> five;
  for (int i = 0; i < 5; ++i) five.push_back(world.add_joint(pin));
  for (const int i : {3, 1, 2}) world.remove_joint(five[i]);
  for (const std::uint32_t expected : {1u, 2u, 3u, 5u}) CHECK(world.add_joint(pin).index == expected);
  CHECK(world.joint_count() == 6);
  for (const JointId id : world.joint_ids()) world.remove_joint(id);
  world.update_settings([](auto& st) { st.contact.solver = ContactSolver::Paper; });
  refused(pin, "paper's contact solver");
}

TEST_CASE("joints: a removed joint lets its body fall", "[joints]") {
  World<4> world = pendulum_world<4>();
  const BodyId bob = world.add_body(ball<4>(0.05, xy<4>(0.0, -0.5)));
  DistanceJointDef<4> rod;
  rod.body_b = bob;
  const JointId joint = world.add_joint(rod);
  for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
  CHECK(world.body(bob).center[1] == Approx(-0.5).margin(1e-4));  // held
  CHECK(world.joint_force(joint)[1] == Approx(world.body(bob).mass * kG).epsilon(1e-3));
  world.remove_joint(joint);
  for (int i = 0; i < 60; ++i) world.step(1.0 / 60.0);
  CHECK(world.body(bob).velocity[1] == Approx(-kG).epsilon(1e-9));  // free fall for 1 s
}

// A frictionless double pendulum: two bars on point joints, the upper pinned to the world, released
// horizontal. Its motion is chaotic, but its energy is a constant of it: the soft step keeps it within 1%
// for 10 s at 60 Hz and at 120 Hz (its joints' springs take a little; the figures are printed).
TEMPLATE_TEST_CASE("joints: a double pendulum keeps its energy", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  for (const double h : {1.0 / 60.0, 1.0 / 120.0}) {
    CAPTURE(h);
    World<N> world = pendulum_world<N>();
    Vec<N> half = Vec<N>::Constant(0.04);
    half[0] = 0.3;
    const BodyId upper = world.add_body(box<N>(half, 500.0, xy<N>(0.3, 0.0)));
    const BodyId lower = world.add_body(box<N>(half, 500.0, xy<N>(0.9, 0.0)));
    PointJointDef<N> top, middle;
    top.body_b = upper;
    top.anchor_b = xy<N>(-0.3, 0.0);
    middle.body_a = upper;
    middle.anchor_a = xy<N>(0.3, 0.0);
    middle.body_b = lower;
    middle.anchor_b = xy<N>(-0.3, 0.0);
    world.add_joint(top);
    world.add_joint(middle);
    const double e0 = world.kinetic_energy() + world.potential_energy();
    // J: its energy above the rest state (both bars hanging straight down), the zero of potential energy
    // that gives "1%" a meaning: released horizontal, the centres stand 0.3 m and 0.9 m above their rest.
    const double scale = world.body(upper).mass * kG * (0.3 + 0.9);
    double worst = 0.0;
    for (int i = 0; i * h < 10.0; ++i) {
      world.step(h);
      worst = std::max(worst, std::abs(world.kinetic_energy() + world.potential_energy() - e0));
    }
    const double end = world.kinetic_energy() + world.potential_energy() - e0;
    INFO("largest energy change " << worst / scale * 100 << "%, at 10 s " << end / scale * 100 << "%");
    CHECK(worst < 0.01 * scale);
  }
}


namespace {

// How far a rotation turns anything off the x-y plane: a turn in that plane alone leaves every axis e_k,
// k >= 2, where it is, so the largest |R e_k ~R - e_k| (about the angle, for small ones).
template <int N>
double off_plane_turn(const Rotor<N>& r) {
  double most = 0.0;
  for (int k = 2; k < N; ++k) most = std::max(most, (rotate(r, Vec<N>(Vec<N>::Unit(k))) - Vec<N>::Unit(k)).norm());
  return most;
}

template <int N>
RevoluteJointDef<N> hinge_to_world(BodyId body, const Vec<N>& anchor_b, const Vec<N>& world_point) {
  RevoluteJointDef<N> def;  // the plane: x-y in the world and in the body (which starts unturned)
  def.body_b = body;
  def.anchor_a = world_point;
  def.anchor_b = anchor_b;
  return def;
}

}  // namespace

// A bar hung on a revolute joint (plane x-y) swings as the physical pendulum: period 2 pi sqrt(I_p/(m g d))
// with the finite-amplitude factor, and the joint's angle is the bar's turn.
TEMPLATE_TEST_CASE("joints: a bar on a revolute joint swings with the physical pendulum's period", "[joints]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0, theta0 = 0.05, a = 0.05, b = 0.4;
  World<N> world = pendulum_world<N>();
  Vec<N> half = Vec<N>::Constant(0.05);
  half[0] = a;
  half[1] = b;
  // Hanging straight down from the pivot at the origin, then turned by theta0 about it (velocity 0).
  const BodyId bar = world.add_body(box<N>(half, 500.0, xy<N>(0.0, -b)));
  const JointId hinge = world.add_joint(hinge_to_world<N>(bar, xy<N>(0.0, b), Vec<N>(Vec<N>::Zero())));
  Body<N>& body = world.body(bar);
  Mat<N> turn = Mat<N>::Identity();
  turn(0, 0) = turn(1, 1) = std::cos(theta0);
  turn(0, 1) = -std::sin(theta0);
  turn(1, 0) = std::sin(theta0);
  body.rotor = rotor_from_matrix<N>(turn);
  body.center = xy<N>(b * std::sin(theta0), -b * std::cos(theta0));
  const double m = body.mass;
  const double ip = m * (a * a + b * b) / 3.0 + m * b * b;
  const double exact = 2 * M_PI * std::sqrt(ip / (m * kG * b)) * std::comp_ellint_1(std::sin(theta0 / 2)) * 2 / M_PI;
  world.step(h);
  CHECK(world.joint_angle(hinge) == Approx(theta0).epsilon(0.01));  // (one step after release)
  const Swing s = swing(world, bar, h, 10.0);
  REQUIRE(s.crossings >= 4);
  CHECK(s.period == Approx(exact).epsilon(0.005));
  CHECK(s.off_plane == 0.0);
  CHECK(off_plane_turn(world.body(bar).rotor) < 1e-9);
  CHECK((world.joint_anchor_b(hinge) - world.joint_anchor_a(hinge)).norm() < 1e-4);
}

// Knocked out of its plane again and again, a hinged bar keeps turning in that plane only: the relative
// rotation's parts off the plane stay small while knocked and vanish at rest.
TEMPLATE_TEST_CASE("joints: a revolute joint keeps its bodies turning in its plane when knocked", "[joints]", D3, D4,
                   D5) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0;
  WorldSettings<N> settings;
  settings.gravity = xy<N>(0.0, -kG);
  World<N> world(settings);
  Vec<N> half = Vec<N>::Constant(0.05);
  half[1] = 0.4;
  const BodyId bar = world.add_body(box<N>(half, 500.0, xy<N>(0.0, -0.4)));
  const JointId hinge = world.add_joint(hinge_to_world<N>(bar, xy<N>(0.0, 0.4), Vec<N>(Vec<N>::Zero())));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double knocked = 0.0;
  // 10 s, a knock every 0.5 s at a random point of the bar in any direction, of the impulse that would
  // change the free bar's velocity by 0.5 m/s (1.6 N s in 3D, 0.016 in 6D: the bar's mass falls with n).
  const double knock = 0.5 * world.body(bar).mass;
  for (int i = 0; i < 1200; ++i) {
    if (i % 60 == 0) {
      Vec<N> j, at;
      for (int k = 0; k < N; ++k) {
        j[k] = unit(rng);
        at[k] = 0.05 * unit(rng);
      }
      at[1] = 0.4 * unit(rng);
      const Body<N>& b = world.body(bar);
      world.apply_impulse_at(bar, Vec<N>(knock * j.normalized()), Vec<N>(b.center + rotate(b.rotor, at)));
    }
    world.step(h);
    knocked = std::max(knocked, off_plane_turn(world.body(bar).rotor));
  }
  for (int i = 0; i < 1200; ++i) world.step(h);  // 10 s more, swinging down on its own
  const double settled = off_plane_turn(world.body(bar).rotor);
  INFO("largest turn off the plane while knocked " << knocked << " rad, 10 s later " << settled << " rad");
  // While knocked: 0.14, 0.27 and 0.25 mrad in 3D, 4D and 5D (measured; issue 45 asks for 1 mrad). A
  // knock's velocity off the plane is taken out by the first sub-step's solve pass at the angular rows'
  // soft mass scale (90% at the default joint_angular_hertz, 240 Hz at 960 sub-steps a second), and the
  // rest moves the bar off the plane for one sub-step before the relax pass removes it: at 120 Hz (mass
  // scale 79%) the bar turned 0.75, 1.5 and 1.6 mrad off it. At rest: round-off.
  CHECK(knocked < 1e-3);
  CHECK(settled < 1e-6);
  CHECK((world.joint_anchor_b(hinge) - world.joint_anchor_a(hinge)).norm() < 1e-3);
}

// Two wheels on one revolute joint at their common centre turn against each other by 5 rad a step (each
// by 2.5 rad, below the pi a step that max_turn allows a body): the joint's angle must count every turn,
// checked against each wheel's own angle, unwrapped step by step from its rotor. (A 2D revolute joint
// without limits takes its angle once a step; turning fast, or driven by a fast motor, every sub-step.)
TEST_CASE("joints: a 2D revolute joint counts the turns of wheels spinning apart fast", "[joints]") {
  const double h = 1.0 / 120.0;
  World<2> world;  // no gravity
  const BodyId a = world.add_body(box<2>(Vec<2>(0.1, 0.1), 1000.0, Vec<2>(0.0, 0.0)));
  const BodyId b = world.add_body(box<2>(Vec<2>(0.1, 0.1), 1000.0, Vec<2>(0.0, 0.0)));
  RevoluteJointDef<2> def;
  def.body_a = a;
  def.body_b = b;
  const bool motor = GENERATE(false, true);
  CAPTURE(motor);
  if (motor) {  // from rest, the motor turns them apart at 600 rad/s within the first sub-step
    def.motor = true;
    def.motor_speed = -600.0;
    def.max_motor_torque = 1e6;
  } else {  // already spinning apart
    world.body(a).angular_velocity[0] = 300.0;
    world.body(b).angular_velocity[0] = -300.0;
  }
  const JointId joint = world.add_joint(def);
  const auto turn = [&](BodyId id) {
    const Vec<2> x = rotate(world.body(id).rotor, Vec<2>(1.0, 0.0));
    return std::atan2(x[1], x[0]);
  };
  double angle_a = 0.0, angle_b = 0.0;  // each wheel's turn, unwrapped: it turns by less than pi a step
  const auto follow = [&](double& angle, double now) { angle += std::remainder(now - angle, 2.0 * M_PI); };
  for (int i = 0; i < 60; ++i) {
    world.step(h);
    follow(angle_a, turn(a));
    follow(angle_b, turn(b));
  }
  INFO("wheels " << angle_a << " and " << angle_b << " rad; joint " << world.joint_angle(joint) << " rad");
  CHECK(std::abs(angle_b - angle_a) > 250.0);  // (about 5 rad a step for 60 steps)
  CHECK(world.joint_angle(joint) == Approx(angle_b - angle_a).epsilon(1e-9));
}

// A motor spins a wheel up to its speed, never with more than its torque: with a torque limit T the
// speed rises at T/I until it is reached.
TEMPLATE_TEST_CASE("joints: a revolute motor reaches its speed within its torque", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0, speed = 3.0, spin_up = 0.5;  // rad/s, s
  World<N> world;  // no gravity
  const BodyId wheel = world.add_body(box<N>(Vec<N>(Vec<N>::Constant(0.1)), 1000.0, Vec<N>(Vec<N>::Zero())));
  // The wheel's moment about its centre in the x-y plane, from its sides: m ((2a)^2 + (2a)^2) / 12; the
  // motor's torque limit spins it up in spin_up seconds.
  const double m = world.body(wheel).mass, inertia = m * (0.04 + 0.04) / 12.0, torque = speed * inertia / spin_up;
  RevoluteJointDef<N> def = hinge_to_world<N>(wheel, Vec<N>(Vec<N>::Zero()), Vec<N>(Vec<N>::Zero()));
  def.motor = true;
  def.motor_speed = speed;
  def.max_motor_torque = torque;
  const JointId motor = world.add_joint(def);
  const auto w = [&] { return world.body(wheel).angular_velocity[Bivector<N>::index(0, 1)]; };
  world.step(h);
  CHECK(w() == Approx(torque / inertia * h).epsilon(1e-6));  // limited: T h / I in a step
  CHECK(world.joint_torque(motor).norm() == Approx(torque).epsilon(1e-9));
  while (world.time() < 1.5 * spin_up) world.step(h);
  CHECK(w() == Approx(speed).epsilon(1e-6));
  CHECK(world.joint_angle(motor) > 0.5 * speed * spin_up);
}

// Angle limits stop a pendulum at its limits.
TEMPLATE_TEST_CASE("joints: revolute limits hold the angle between them", "[joints]", D2, D3, D4) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0;
  World<N> world = pendulum_world<N>();
  Vec<N> half = Vec<N>::Constant(0.05);
  half[1] = 0.4;
  BodyDef<N> def = box<N>(half, 500.0, xy<N>(0.0, -0.4));
  def.angular_velocity = Bivector<N>::basis(0, 1) * 4.0;  // swinging up hard
  def.velocity = xy<N>(1.6, 0.0);                       // (the centre moving with it, 0.4 m from the pivot)
  const BodyId bar = world.add_body(def);
  RevoluteJointDef<N> hinge = hinge_to_world<N>(bar, xy<N>(0.0, 0.4), Vec<N>(Vec<N>::Zero()));
  hinge.limit = true;
  hinge.lower_angle = -0.3;
  hinge.upper_angle = 0.3;
  const JointId joint = world.add_joint(hinge);
  double low = 0.0, high = 0.0;
  for (int i = 0; i < 600; ++i) {
    world.step(h);
    low = std::min(low, world.joint_angle(joint));
    high = std::max(high, world.joint_angle(joint));
  }
  INFO("angle stayed in [" << low << ", " << high << "] rad");
  // Free, its energy (1/2 I_p w^2, I_p = m (a^2 + b^2)/3 + m b^2) would carry it to 0.97 rad; the limit stops
  // it within a hundredth of a radian of 0.3.
  CHECK(high < 0.31);
  CHECK(high > 0.29);
  CHECK(low > -0.31);
}

// A rigid weld holds a cantilever: the bar stays where it was welded, turned by less than a milliradian.
TEMPLATE_TEST_CASE("joints: a weld holds a cantilever", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  World<N> world = pendulum_world<N>();
  Vec<N> half = Vec<N>::Constant(0.03);
  half[0] = 0.3;
  const BodyId bar = world.add_body(box<N>(half, 500.0, xy<N>(0.3, 0.0)));
  WeldJointDef<N> weld;
  weld.body_b = bar;
  weld.anchor_b = xy<N>(-0.3, 0.0);  // its left end, at the origin
  const JointId joint = world.add_joint(weld);
  for (int i = 0; i < 300; ++i) world.step(1.0 / 60.0);
  const Body<N>& b = world.body(bar);
  INFO("centre " << b.center.transpose() << ", turn " << (log<N>(b.rotor) * -2.0).norm() << " rad");
  CHECK((b.center - xy<N>(0.3, 0.0)).norm() < 1e-3);
  CHECK((log<N>(b.rotor) * -2.0).norm() < 1e-3);
  CHECK(b.velocity.norm() < 1e-6);
  // It carries the bar's weight and the moment of it about the weld: m g up at the anchor, and m g 0.3 N m.
  CHECK(world.joint_force(joint)[1] == Approx(b.mass * kG).epsilon(1e-3));
  CHECK(world.joint_torque(joint).norm() == Approx(b.mass * kG * 0.3).epsilon(1e-2));
}

// A soft weld is a spring in each of its blocks: its point rows of stiffness K^-1 w^2 and its angular
// rows of stiffness M^-1 w^2 (w = 2 pi frequency, K and M the rows' effective masses, as Box2D v3's soft
// constraints). A cantilever welded softly at its left end to the world settles where those springs
// carry its weight: the anchor sags by K_yy m g / w^2 (K_yy = 1/m + d^2/I, d the anchor's lever, I the
// bar's moment in the x-y plane about its centre), and the bar turns by m g d / (I w^2), so its centre
// drops by the sum of the anchor's sag and d sin(turn).
TEMPLATE_TEST_CASE("joints: a soft weld sags as its frequency predicts", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double d = 0.3, frequency = 10.0, w = 2.0 * M_PI * frequency;
  World<N> world = pendulum_world<N>();
  Vec<N> half = Vec<N>::Constant(0.03);
  half[0] = d;
  const BodyId bar = world.add_body(box<N>(half, 500.0, xy<N>(d, 0.0)));
  WeldJointDef<N> weld;
  weld.body_b = bar;
  weld.anchor_b = xy<N>(-d, 0.0);
  weld.frequency = frequency;
  weld.damping_ratio = 1.0;
  world.add_joint(weld);
  for (int i = 0; i < 180; ++i) world.step(1.0 / 60.0);  // 3 s: thirty periods, critically damped
  const Body<N>& b = world.body(bar);
  const double m = b.mass, inertia = m * (half[0] * half[0] + half[1] * half[1]) / 3.0;
  const double turn = m * kG * d / (inertia * w * w);
  const double anchor_sag = (1.0 / m + d * d / inertia) * m * kG / (w * w);
  const double drop = anchor_sag + d * std::sin(turn);
  const double measured_turn = -(log<N>(b.rotor) * -2.0)[Bivector<N>::index(0, 1)];
  INFO("turn " << measured_turn << " rad (predicted " << turn << "), centre dropped " << -b.center[1] << " m (predicted "
               << drop << ")");
  // 1%: the prediction is the small-deflection one (the lever shortens by d (1 - cos turn), 0.03%), and
  // the bar is still settling by less than that after 3 s.
  CHECK(measured_turn == Approx(turn).epsilon(0.01));
  CHECK(-b.center[1] == Approx(drop).epsilon(0.01));
  CHECK(b.velocity.norm() < 1e-4);
}

namespace {

// A unit axis at angle acos(0.6) to straight down, leaning into x (and in 3D and up into the last axis).
template <int N>
Vec<N> leaning_axis() {
  Vec<N> a = xy<N>(0.8, -0.6);
  if (N >= 3) {
    a[0] = 0.48;
    a[N - 1] = 0.64;
  }
  return a;
}

}  // namespace

// A body on a prismatic joint to the world, gravity at an angle to the axis: it slides at g cos(angle)
// (the axis' share of gravity; the joint's rows across the axis carry the rest) and never turns, though
// it hangs from an anchor off its centre, whose reaction would turn a body on a point joint.
TEMPLATE_TEST_CASE("joints: a prismatic slider accelerates at g cos(angle) and never turns", "[joints]", D2, D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0, cosine = 0.6;
  World<N> world = pendulum_world<N>();
  const Vec<N> half = Vec<N>::Constant(0.1);
  const BodyId block = world.add_body(box<N>(half, 500.0, Vec<N>(Vec<N>::Zero())));
  PrismaticJointDef<N> def;
  def.body_b = block;
  def.anchor_b = half;  // a corner
  def.anchor_a = half;
  def.axis_a = leaning_axis<N>();
  const JointId slider = world.add_joint(def);
  for (int i = 0; i < 60; ++i) world.step(h);
  const Body<N>& b = world.body(block);
  const Vec<N> axis = leaning_axis<N>();
  const double t = world.time(), along = b.center.dot(axis), speed = b.velocity.dot(axis);
  // The joint's rows are stiff springs (joint_hertz 120 Hz): under the anchor's moment about the centre,
  // r_b ^ F with F = -m g_across, the angular rows hold the block turned by |I^-1 (r_b ^ F)| / w^2, w =
  // 2 pi 120 Hz (the cube's inverse inertia is 3 / (2 m a^2) in every plane), and no further.
  const Vec<N> gravity = xy<N>(0.0, -kG);
  const Vec<N> across = -b.mass * (gravity - axis * axis.dot(gravity));
  const double w = 2.0 * M_PI * 120.0;
  const double stretch_turn = outer<N>(half, across).norm() * 3.0 / (2.0 * b.mass * half[0] * half[0]) / (w * w);
  const double turned = (log<N>(b.rotor) * -2.0).norm();
  INFO("after " << t << " s: " << along << " m along the axis at " << speed << " m/s, off the line by "
                << (b.center - along * axis).norm() << " m, turned by " << turned << " rad (the rows' stretch "
                << stretch_turn << ")");
  // Velocity: symplectic Euler's is exact under constant acceleration, so to round-off and the soft
  // rows' leftovers (1e-6). Distance: (1/2) a t^2 (1 + 1/n) for n = 480 sub-steps: 0.2% over, bound 0.5%.
  CHECK(speed == Approx(kG * cosine * t).epsilon(1e-6));
  CHECK(along == Approx(0.5 * kG * cosine * t * t).epsilon(0.005));
  // On its line but for the stretch: the turn moves the centre from the anchor by at most |r_b| turn, and
  // the point rows stretch by |K F| / w^2 <= |F| (1 + 3 n / 2) / (m w^2) (K = 1/m + [r_b]^T I^-1 [r_b]).
  const double stretch = half.norm() * stretch_turn + across.norm() * (1.0 + 1.5 * N) / (b.mass * w * w);
  CHECK((b.center - along * axis).norm() < stretch);
  CHECK((b.velocity - speed * axis).norm() < 1e-6);
  CHECK(turned == Approx(stretch_turn).epsilon(0.01));  // turned by the stretch (to 0.05%), not turning
  CHECK(b.angular_velocity.norm() < 1e-6);  // rad/s: settled (4e-8 in 6D)
  CHECK(world.joint_translation(slider) == Approx(along).margin(stretch));  // (the anchor's, not the centre's)
  // The joint carries gravity's part across the axis: m g sin(angle) (0.8 m g), none along it.
  const Vec<N> force = world.joint_force(slider);
  CHECK(force.dot(axis) == Approx(0.0).margin(1e-6 * b.mass * kG));
  CHECK(force.norm() == Approx(0.8 * b.mass * kG).epsilon(1e-6));
}

// Two free bodies on a prismatic joint, thrown spinning: the joint's forces are internal (linear momentum
// kept to round-off), b keeps its orientation relative to a, and b stays on a's axis as it turns.
TEMPLATE_TEST_CASE("joints: a prismatic joint turns its bodies together", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0;
  World<N> world;  // no gravity
  BodyDef<N> da = box<N>(Vec<N>(Vec<N>::Constant(0.2)), 1000.0, Vec<N>(Vec<N>::Zero()));
  da.angular_velocity = Bivector<N>::basis(0, 1) * 2.0;
  if (N >= 3) da.angular_velocity = da.angular_velocity + Bivector<N>::basis(1, N - 1) * 1.0;
  da.velocity = xy<N>(0.5, 0.0);
  Vec<N> half_b = Vec<N>::Constant(0.05);
  BodyDef<N> db = box<N>(half_b, 1000.0, xy<N>(0.5, 0.0));
  db.velocity = xy<N>(1.0, 0.3);
  const BodyId a = world.add_body(da), b = world.add_body(db);
  PrismaticJointDef<N> def;
  def.body_a = a;
  def.body_b = b;
  def.anchor_a = Vec<N>(Vec<N>::Zero());
  def.anchor_b = Vec<N>(Vec<N>::Zero());
  def.axis_a = Vec<N>::Unit(0);
  def.limit = true;
  def.lower_translation = 0.3;
  def.upper_translation = 1.0;
  const JointId slider = world.add_joint(def);
  const auto momentum = [&] {
    return Vec<N>(world.body(a).mass * world.body(a).velocity + world.body(b).mass * world.body(b).velocity);
  };
  const Vec<N> p0 = momentum();
  const Rotor<N> relative0 = reverse(world.body(a).rotor) * world.body(b).rotor;
  double off_axis = 0.0, relative_turn = 0.0, low = 1.0, high = 0.0;
  for (int i = 0; i < 300; ++i) {
    world.step(h);
    const Body<N>& ba = world.body(a);
    const Body<N>& bb = world.body(b);
    const Vec<N> axis = rotate(ba.rotor, Vec<N>(Vec<N>::Unit(0)));
    const Vec<N> sep = bb.center - ba.center;
    off_axis = std::max(off_axis, (sep - axis * axis.dot(sep)).norm());
    relative_turn = std::max(relative_turn, (log<N>(reverse(relative0) * reverse(ba.rotor) * bb.rotor) * -2.0).norm());
    low = std::min(low, world.joint_translation(slider));
    high = std::max(high, world.joint_translation(slider));
  }
  INFO("off the axis by " << off_axis << " m, turned by " << relative_turn << " rad; translation in [" << low << ", "
                          << high << "] m");
  CHECK((momentum() - p0).norm() < 1e-9 * p0.norm());
  CHECK(off_axis < 1e-3);
  CHECK(relative_turn < 1e-3);
  // Spun out along the axis by the turning, it reaches the upper limit and stays within 1 cm of it.
  CHECK(high > 0.99);
  CHECK(high < 1.01);
  CHECK(low > 0.29);
}

// A prismatic motor drives its body to its speed with no more than its force (m v / spin_up: the speed
// rises at F / m until reached); a limit stops it.
TEMPLATE_TEST_CASE("joints: a prismatic motor reaches its speed within its force and stops at its limit", "[joints]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 120.0, speed = 2.0, spin_up = 0.25, stop = 1.0;  // m/s, s, m
  World<N> world;  // no gravity
  const BodyId block = world.add_body(box<N>(Vec<N>(Vec<N>::Constant(0.1)), 1000.0, Vec<N>(Vec<N>::Zero())));
  const double m = world.body(block).mass, force = m * speed / spin_up;
  PrismaticJointDef<N> def;
  def.body_b = block;
  def.axis_a = Vec<N>::Unit(N - 1);
  def.motor = true;
  def.motor_speed = speed;
  def.max_motor_force = force;
  def.limit = true;
  def.lower_translation = -stop;
  def.upper_translation = stop;
  const JointId motor = world.add_joint(def);
  const auto v = [&] { return world.body(block).velocity[N - 1]; };
  world.step(h);
  CHECK(v() == Approx(force / m * h).epsilon(1e-9));  // limited: F h / m in a step
  CHECK(world.joint_force(motor).norm() == Approx(force).epsilon(1e-9));
  double fastest_gain = 0.0;
  while (world.time() < 1.5 * spin_up) {
    const double before = v();
    world.step(h);
    fastest_gain = std::max(fastest_gain, v() - before);
  }
  CHECK(fastest_gain < force / m * h * (1.0 + 1e-9));  // never more than F
  CHECK(v() == Approx(speed).epsilon(1e-9));
  double furthest = 0.0;
  for (int i = 0; i < 120; ++i) {
    world.step(h);
    furthest = std::max(furthest, world.joint_translation(motor));
  }
  INFO("furthest " << furthest << " m; limit " << stop << " m");
  CHECK(furthest < stop + 0.005);
  CHECK(world.joint_translation(motor) == Approx(stop).margin(0.005));
  CHECK(std::abs(v()) < 1e-6);  // held at the limit against the motor
}

// Newton's cradle: five steel balls (radius 5 cm) on 0.5 m rods, restitution 1, frictionless; the first
// released from 30 degrees. Each collision passes the first ball's speed down the row, so the last ball
// swings up to the first's drop height (within 5%, issue 45) and the first is left nearly at rest.
// The balls hang 1 cm apart: the soft step applies restitution, as Box2D v3 and Jolt do, with each
// contact's approach speed at the start of the step, so balls that touch are struck at once and leave as
// a block (the last rises to 11% of the height); 1 cm is more than a struck ball travels in the rest of
// its step (half the speed times 1/120 s, 4.8 mm), so each collision has a step of its own, ball to ball.
TEMPLATE_TEST_CASE("joints: Newton's cradle passes the swing to its last ball", "[joints]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double r = 0.05, rod = 0.5, gap = 0.01, theta0 = M_PI / 6.0, top = 1.0, h = 1.0 / 120.0;
  WorldSettings<N> settings;
  settings.gravity = xy<N>(0.0, -kG);
  settings.contact.allow_sleep = false;
  settings.contact.restitution_threshold = 0.1;
  World<N> world(settings);
  std::vector<BodyId> balls;
  for (int i = 0; i < 5; ++i) {
    const double x = (i - 2) * (2.0 * r + gap);
    BodyDef<N> def = ball<N>(r, xy<N>(x, top - rod));
    def.material = Material{1.0, 0.0, 0.0};
    if (i == 0) def.position = xy<N>(x - rod * std::sin(theta0), top - rod * std::cos(theta0));
    balls.push_back(world.add_body(def));
    DistanceJointDef<N> hang;
    hang.anchor_a = xy<N>(x, top);
    hang.body_b = balls.back();
    world.add_joint(hang);
  }
  const double drop = rod * (1.0 - std::cos(theta0));
  // The swing down takes a quarter period (0.36 s), the last ball's swing up another: its highest point
  // by 0.75 s. The first ball's rise is taken after the impact (0.45 s on).
  std::vector<double> rise(5, 0.0);
  while (world.time() < 0.75) {
    world.step(h);
    for (int i = world.time() > 0.45 ? 0 : 1; i < 5; ++i)
      rise[i] = std::max(rise[i], world.body(balls[i]).center[1] - (top - rod));
  }
  INFO("drop " << drop << " m; after the impact the balls rose by " << rise[0] << ", " << rise[1] << ", " << rise[2]
               << ", " << rise[3] << ", " << rise[4] << " m");
  CHECK(rise[4] == Approx(drop).epsilon(0.05));
  for (int i = 0; i < 4; ++i) CHECK(rise[i] < 0.05 * drop);
}

// The joints' stability under load: a body held at two anchors a lever r apart by a tension T has a
// stiffness against turning of T r (its anchors swing sideways against the pull), so it turns at
// w = sqrt(T r / I). The sub-step integrates that explicitly, through the lever arms of its start, and
// like any such scheme holds only while h_sub w stays below about 1.5 (measured on this column at 4
// sub-steps of a 60 Hz step: 1.46 holds, 1.59 swings up to the max_turn cap; docs/joints.md). Ten disks
// of 0.5 kg on revolute joints carry an end mass that puts h_sub w at 1.3 in the top disk: it hangs still.
TEMPLATE_TEST_CASE("joints: a column of light disks holds a heavy end mass within the sub-step's limit", "[joints]", D2,
                   D3, D4) {
  constexpr int N = TestType::value;
  const double h = 1.0 / 60.0, h_sub = h / 4.0, radius = 0.4;
  WorldSettings<N> settings;
  settings.gravity = xy<N>(0.0, -kG);
  settings.contact.allow_sleep = false;
  settings.contact.substeps = 4;
  settings.contact.joint_hertz = 60.0;
  World<N> world(settings);
  BodyDef<N> disk;
  disk.type = BodyType::Static;
  std::vector<BodyId> ids{world.add_body(disk)};
  disk.type = BodyType::Dynamic;
  disk.mass = 0.5;
  disk.inertia = BivMat<N>::Identity() * (0.5 * disk.mass * radius * radius);
  const double moment = disk.inertia(0, 0);
  const double tension = std::pow(1.3 / h_sub, 2) * moment / 1.0;  // T r / I = (1.3 / h_sub)^2, r = 1 m
  for (int i = 1; i <= 10; ++i) {
    disk.position = xy<N>(0.0, -i);
    if (i == 10) disk.mass = tension / kG - 8 * 0.5;  // (the eight disks below the top one)
    disk.angular_velocity = Bivector<N>::basis(0, 1) * (0.01 * ((i * 37) % 7 - 3));  // a small stir
    ids.push_back(world.add_body(disk));
    RevoluteJointDef<N> pin;
    pin.body_a = ids[std::size_t(i) - 1];
    pin.body_b = ids.back();
    pin.anchor_a = xy<N>(0.0, -0.5);
    pin.anchor_b = xy<N>(0.0, 0.5);
    world.add_joint(pin);
  }
  double spin = 0.0;
  for (int i = 0; i < 600; ++i) {
    world.step(h);
    for (const Body<N>& b : world.bodies()) spin = std::max(spin, b.angular_velocity.norm());
  }
  INFO("end mass " << tension / kG << " kg, tension " << tension << " N; fastest spin " << spin << " rad/s");
  CHECK(spin < 1.0);
  CHECK(std::abs(world.body(ids.back()).center[0]) < 1e-3);
}

// What a viewer draws (World::joint_ids, joint_geometry): the live joints in slot order, their anchors
// where the bodies carry them, a revolute's plane turned with body a and body b's vector turned in it by
// the joint's angle, a prismatic's axis turned with body a. Expected values from rotation matrices built
// here, not from the rotors the world holds.
TEMPLATE_TEST_CASE("joints: a world lists its joints and where they are now", "[joints]", D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  World<N> world = pendulum_world<N>();
  const BodyId door = world.add_body(box<N>(Vec<N>::Constant(0.1), 500.0, xy<N>(0.5, 0.0)));
  const BodyId carriage = world.add_body(box<N>(Vec<N>::Constant(0.1), 500.0, xy<N>(0.0, 2.0)));
  const BodyId slider = world.add_body(box<N>(Vec<N>::Constant(0.05), 500.0, xy<N>(0.3, 2.0)));
  RevoluteJointDef<N> hinge;  // the door turns in the x-z plane about the world point (0.4, 0, ..)
  hinge.body_b = door;
  hinge.anchor_a = xy<N>(0.4, 0.0);
  hinge.anchor_b = xy<N>(-0.1, 0.0);
  hinge.plane_u_a = hinge.plane_u_b = Vec<N>::Unit(0);
  hinge.plane_v_a = hinge.plane_v_b = Vec<N>::Unit(2);
  const JointId h = world.add_joint(hinge);
  PointJointDef<N> spare;
  spare.body_b = carriage;
  spare.anchor_a = xy<N>(0.0, 2.1);
  spare.anchor_b = xy<N>(0.0, 0.1);
  const JointId removed = world.add_joint(spare);
  PrismaticJointDef<N> rail;  // the slider runs along the carriage's x axis
  rail.body_a = carriage;
  rail.body_b = slider;
  rail.anchor_a = xy<N>(0.1, 0.0);
  rail.anchor_b = xy<N>(-0.2, 0.0);
  const JointId p = world.add_joint(rail);
  world.remove_joint(removed);

  const std::vector<JointId> ids = world.joint_ids();
  REQUIRE(ids.size() == 2);
  CHECK(ids[0] == h);
  CHECK(ids[1] == p);

  // Turn the door by theta in its plane about the hinge, and the carriage (body a of the rail) by phi in
  // the x-y plane about its centre.
  const double theta = 0.7, phi = 0.3;
  auto plane_turn = [](int i, int j, double angle) {  // e_i toward e_j
    Mat<N> m = Mat<N>::Identity();
    m(i, i) = m(j, j) = std::cos(angle);
    m(j, i) = std::sin(angle);
    m(i, j) = -std::sin(angle);
    return m;
  };
  const Mat<N> door_turn = plane_turn(0, 2, theta), carriage_turn = plane_turn(0, 1, phi);
  world.body(door).rotor = rotor_from_matrix<N>(door_turn);
  world.body(door).center = xy<N>(0.4, 0.0) + door_turn * xy<N>(0.1, 0.0);
  world.body(carriage).rotor = rotor_from_matrix<N>(carriage_turn);

  const JointGeometry<N> g = world.joint_geometry(h);
  CHECK(g.type == JointType::Revolute);
  CHECK(!g.body_a);
  CHECK(g.body_b == door);
  CHECK((g.anchor_a - xy<N>(0.4, 0.0)).norm() < 1e-12);
  CHECK((g.anchor_b - xy<N>(0.4, 0.0)).norm() < 1e-12);  // the door turned about its hinge
  CHECK((g.plane_u - Vec<N>::Unit(0)).norm() < 1e-12);
  CHECK((g.plane_v - Vec<N>::Unit(2)).norm() < 1e-12);
  CHECK((g.plane_u_b - (std::cos(theta) * Vec<N>::Unit(0) + std::sin(theta) * Vec<N>::Unit(2))).norm() < 1e-12);
  CHECK(g.axis == Vec<N>::Zero());

  const JointGeometry<N> r = world.joint_geometry(p);
  CHECK(r.type == JointType::Prismatic);
  CHECK((r.body_a && *r.body_a == carriage));
  CHECK(r.body_b == slider);
  CHECK((r.anchor_a - (xy<N>(0.0, 2.0) + carriage_turn * xy<N>(0.1, 0.0))).norm() < 1e-12);
  CHECK((r.axis - carriage_turn.col(0)).norm() < 1e-12);
  CHECK(r.plane_u == Vec<N>::Zero());
  CHECK_THROWS_WITH(world.joint_geometry(removed), Catch::Contains("is not a live joint"));

  // A joint added after the removal takes the freed slot with a new generation.
  const JointId again = world.add_joint(spare);
  CHECK(again.index == removed.index);
  CHECK(again.generation != removed.generation);
  CHECK(world.joint_ids() == std::vector<JointId>{h, again, p});
}
