// Contact events (core/src/contact/events.cpp): what a step reports after it (begin and end events with
// impulse, point and approach speed, checked against the impulse-momentum balance), sorted by pair, and
// the same on every run: bit-identical states and events, also from a copied world.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>

#include "contact_bodies.hpp"
#include "wedge/scenes/builders.hpp"
#include "contact/contact_system.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

template <int N>
World<N> ball_drop(double e, double drop, double radius) {
  WorldSettings<N> s;
  s.gravity = -9.81 * Vec<N>::Unit(1);
  s.contact.allow_sleep = false;
  World<N> w(s);
  scenes::add_ground(w);
  BodyDef<N> b = body_def<N>(std::make_shared<const Shape<N>>(Shape<N>::ball(radius)), 1000.0);
  b.position[1] = radius + drop;
  b.material.restitution = e;
  w.add_body(b);
  return w;
}

}  // namespace

TEST_CASE("a bouncing ball reports one begin event with impulse m (1 + e) v, then an end event", "[contact][events]") {
  const double h = 1.0 / 1000.0, e = 0.5, drop = 1.0, radius = 0.2;
  World<3> w = ball_drop<3>(e, drop, radius);
  const BodyId ball{1};
  const double m = w.body(ball).mass;
  int begins = 0, ends = 0;
  ContactBeginEvent<3> first;
  double v_before = 0.0, v_after = 0.0;
  for (int i = 0; i < 800; ++i) {
    const double v = w.body(ball).velocity[1];
    w.step(h);
    for (const ContactBeginEvent<3>& ev : w.contact_begin_events()) {
      if (begins++ == 0) {
        first = ev;
        v_before = v;
        v_after = w.body(ball).velocity[1];
      }
    }
    ends += int(w.contact_end_events().size());
    if (begins && w.body(ball).velocity[1] > 0.0 && w.body(ball).center[1] > radius + 0.1) break;
  }
  REQUIRE(begins == 1);
  CHECK(ends == 1);
  CHECK(first.a.index == 0);
  CHECK(first.b.index == 1);
  CHECK((first.normal - Vec<3>::UnitY()).norm() < 1e-12);
  // Impulse-momentum balance over the step: j = m (v_after - v_before) + m g h (gravity acted too).
  CHECK(first.normal_impulse == Approx(m * (v_after - v_before) + m * 9.81 * h).epsilon(1e-9));
  // Analytically j = m (1 + e) v_impact, v_impact = sqrt(2 g H); the step bounces up to h v early,
  // which changes v by less than g h: 1%.
  const double v_impact = std::sqrt(2.0 * 9.81 * drop);
  CHECK(first.normal_impulse == Approx(m * (1.0 + e) * v_impact).epsilon(0.01));
  CHECK(first.approach_speed == Approx(v_impact).epsilon(0.01));
  // The point is under the ball, at most h v_impact above the ground.
  CHECK(std::hypot(first.point[0], first.point[2]) < 1e-9);
  CHECK(first.point[1] >= -1e-9);
  CHECK(first.point[1] <= h * v_impact + 1e-9);
}

TEST_CASE("a resting box begins touching once, not in every step", "[contact][events]") {
  WorldSettings<4> s;
  s.gravity = -9.81 * Vec<4>::Unit(1);
  s.contact.allow_sleep = false;
  World<4> w(s);
  scenes::add_ground(w);
  scenes::add_box_tower(w, 1);
  int begins = 0, ends = 0;
  for (int i = 0; i < 240; ++i) {
    w.step(1.0 / 120.0);
    begins += int(w.contact_begin_events().size());
    ends += int(w.contact_end_events().size());
  }
  CHECK(begins == 1);
  CHECK(ends == 0);
  const std::vector<ContactInfo<4>> contacts = w.contacts();
  REQUIRE(contacts.size() == 1);
  CHECK(contacts[0].touching);
  // The 8 corners carry the weight: sum of impulses = m g h.
  double total = 0.0;
  for (int k = 0; k < contacts[0].manifold.count; ++k) total += contacts[0].normal_impulse[k];
  CHECK(contacts[0].manifold.count == 8);
  CHECK(total == Approx(w.body(BodyId{1}).mass * 9.81 / 120.0).epsilon(1e-6));
}

TEST_CASE("contact steps are bit-identical: the same run twice, and a copied world", "[contact][determinism]") {
  auto make = [] {
    WorldSettings<3> s;
    s.gravity = -9.81 * Vec<3>::Unit(1);
    World<3> w(s);
    scenes::add_ground(w);
    scenes::add_box_pile(w, 60, 3);
    return w;
  };
  World<3> a = make(), b = make();
  std::vector<std::uint64_t> events_a, events_b;
  for (int i = 0; i < 150; ++i) {
    a.step(1.0 / 60.0);
    b.step(1.0 / 60.0);
    for (const auto& e : a.contact_begin_events()) events_a.push_back(std::uint64_t(e.a.index) << 32 | e.b.index);
    for (const auto& e : b.contact_begin_events()) events_b.push_back(std::uint64_t(e.a.index) << 32 | e.b.index);
  }
  CHECK(a.state_hash() == b.state_hash());
  CHECK(events_a == events_b);
  CHECK(events_a.size() > 50);
  // Events of one step are sorted by pair.
  World<3> c = a;  // a copy carries the contact state (warm starts, sleep timers) along
  for (int i = 0; i < 100; ++i) {
    a.step(1.0 / 60.0);
    c.step(1.0 / 60.0);
    const auto& ev = a.contact_begin_events();
    for (std::size_t k = 1; k < ev.size(); ++k)
      CHECK((ev[k - 1].a.index < ev[k].a.index || (ev[k - 1].a.index == ev[k].a.index && ev[k - 1].b.index < ev[k].b.index)));
  }
  CHECK(a.state_hash() == c.state_hash());
}

