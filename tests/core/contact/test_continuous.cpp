// Continuous collision (ContactSettings::continuous, core/src/contact/continuous.cpp), 3D to 6D at the
// default step of 1/120 s:
//   - throws as hands make them, a thin plate (1 cm) or a long rod (1 m) flung at 50 m/s, tumbling end
//     over end at 0 to 100 rad/s, at a static wall 1 cm thick, from 8 starting angles and 4 distances
//     (so each meets the wall at a different point of a step): the body's centre never reaches the far
//     half of the wall, every state stays finite, and with continuous collision off some of the same
//     throws do go through (what the check is for). The test prints how often a corner still comes out
//     of the far face and how often the soft step gains energy: known limits (docs/contact.md);
//   - a box sliding fast along a static floor is not held back by the floor it touches: its motion is
//     bit for bit the one with continuous collision off.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <memory>

#include "test_util.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

constexpr double kStep = 1.0 / 120.0;
constexpr double kWallHalf = 0.005;  // m: the wall is 1 cm thick, x in [-0.005, 0.005]

template <int N>
BivMat<N> box_inertia(const Vec<N>& h, double mass) {
  BivMat<N> inertia = BivMat<N>::Zero();
  for (int i = 0, k = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j, ++k) inertia(k, k) = mass * (h[i] * h[i] + h[j] * h[j]) / 3.0;
  return inertia;
}

// The farthest any corner of the box reaches along +x.
template <int N>
double front(const Body<N>& b, const Vec<N>& h) {
  const Mat<N> r = to_matrix(b.rotor);
  double x = -1e300;
  for (int m = 0; m < (1 << N); ++m) {
    Vec<N> c;
    for (int i = 0; i < N; ++i) c[i] = (m >> i & 1) ? h[i] : -h[i];
    x = std::max(x, b.center[0] + r.row(0).dot(c));
  }
  return x;
}

struct Throw {
  bool crossed = false;      // the centre reached the wall's far half (x > 0): the body went through
  bool poked_out = false;    // some corner came out of the wall's far face (x > 0.005)
  double energy_gain = 0.0;  // J, the largest rise of kinetic energy over the throw
  bool finite = true;
};

// One throw of a box of half extents h at the wall: from x = start, at `speed` along +x, tumbling at
// `spin` in the plane e01 from the angle `angle`, for 0.3 s.
template <int N>
Throw throw_at_wall(const Vec<N>& h, double speed, double spin, double angle, double start, bool continuous) {
  World<N> w;
  w.update_settings([&](auto& s) { s.contact.continuous = continuous; });
  BodyDef<N> wall;
  wall.type = BodyType::Static;
  Vec<N> wh = Vec<N>::Constant(2.0);
  wh[0] = kWallHalf;
  wall.shape = std::make_shared<const Shape<N>>(Shape<N>::box(wh));
  w.add_body(wall);
  BodyDef<N> def;
  def.shape = std::make_shared<const Shape<N>>(Shape<N>::box(h));
  def.position[0] = start;
  def.rotor = exp<N>(Bivector<N>::basis(0, 1) * (-0.5 * angle));
  def.velocity[0] = speed;
  def.angular_velocity = Bivector<N>::basis(0, 1) * spin;
  def.inertia = box_inertia<N>(h, def.mass);
  const BodyId id = w.add_body(def);
  Throw out;
  const double e0 = w.body(id).kinetic_energy();
  for (int i = 0; i < int(0.3 / kStep); ++i) {
    w.step(kStep);
    const Body<N>& b = w.body(id);
    out.crossed |= b.center[0] > 0.0;
    out.poked_out |= front(b, h) > kWallHalf;
    out.energy_gain = std::max(out.energy_gain, b.kinetic_energy() - e0);
    out.finite &= all_finite(b.center) && all_finite(b.angular_velocity.c) && all_finite(b.velocity);
  }
  return out;
}

template <int N>
void check_throws(const char* what, const Vec<N>& h) {
  const double speed = 50.0;
  int through_without = 0, through_with = 0, poked = 0, gained = 0, throws = 0;
  double worst_gain = 0.0;
  for (const double spin : {0.0, 30.0, 100.0})
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 4; ++d) {
        const double angle = a * M_PI / 8.0;
        const double start = -1.2 - d * speed * kStep / 4.0;  // a quarter step apart
        const Throw with = throw_at_wall<N>(h, speed, spin, angle, start, true);
        const Throw without = throw_at_wall<N>(h, speed, spin, angle, start, false);
        INFO(N << "D " << what << ": spin " << spin << " rad/s, angle " << angle << ", start " << start);
        ++throws;
        through_without += without.crossed;
        through_with += with.crossed;
        CHECK(!with.crossed);
        CHECK(with.finite);
        poked += with.poked_out;
        gained += with.energy_gain > 1e-9 * 0.5 * speed * speed;
        worst_gain = std::max(worst_gain, with.energy_gain / (0.5 * speed * speed));
      }
  // The figures docs/contact.md quotes: how often a corner still came out of the far face (a plate's
  // edge turning against the wall embeds, see "Known limits") and how often, and by how much, the
  // soft step gained kinetic energy on a body spinning against the wall.
  std::printf("%dD %s: %d of %d throws go through without continuous collision, %d with it; a corner "
              "pokes out in %d; kinetic energy rises in %d (at most %.2f times the throw's)\n",
              N, what, through_without, throws, through_with, poked, gained, worst_gain);
  CHECK(through_without > 0);  // the check can fail: without the sweep, throws do go through
}

}  // namespace

TEMPLATE_TEST_CASE("a thin plate or long rod thrown at 50 m/s tumbling at up to 100 rad/s never passes a 1 cm wall",
                   "[continuous][contact]", D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> plate = Vec<N>::Constant(0.2), rod = Vec<N>::Constant(0.02);
  plate[1] = 0.005;  // 40 cm across, 1 cm thick
  rod[0] = 0.5;      // 1 m long, 4 cm thick
  check_throws<N>("plate", plate);
  check_throws<N>("rod", rod);
}

TEMPLATE_TEST_CASE("a box sliding at 20 m/s on a static floor is not held back by the floor", "[continuous][contact]",
                   D3, D4) {
  constexpr int N = TestType::value;
  Vec<N> end[2];
  for (const bool continuous : {false, true}) {
    World<N> w;
    w.update_settings([&](auto& s) { s.gravity[1] = -9.81; s.contact.continuous = continuous; });
    BodyDef<N> floor;
    floor.type = BodyType::Static;
    Vec<N> fh = Vec<N>::Constant(50.0);
    fh[1] = 0.5;
    floor.shape = std::make_shared<const Shape<N>>(Shape<N>::box(fh));
    floor.position[1] = -0.5;
    w.add_body(floor);
    BodyDef<N> box;
    const Vec<N> h = Vec<N>::Constant(0.1);
    box.shape = std::make_shared<const Shape<N>>(Shape<N>::box(h));
    box.position[1] = 0.1;
    box.velocity[0] = 20.0;
    box.inertia = box_inertia<N>(h, box.mass);
    box.material.friction = 0.0;
    box.material.kinetic_friction = 0.0;
    const BodyId id = w.add_body(box);
    for (int i = 0; i < 120; ++i) w.step(kStep);
    end[continuous] = w.body(id).center;
  }
  INFO("without: " << end[0].transpose() << "; with: " << end[1].transpose());
  CHECK(end[0][0] > 19.0);  // frictionless: it slid on at nearly 20 m/s for 1 s
  CHECK(end[1] == end[0]);
}
