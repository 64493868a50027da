// The constraint graph (core/src/contact/constraint_graph.cpp): colours, and the uncoloured group a body
// in more constraints than colours sends the rest to.
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

// The soft step solves its constraints colour by colour (32 colours; colour_constraints). A
// plank under 40 boxes takes part in 41 constraints, so 9 of them go to the last, uncoloured group: every
// constraint must still be solved once per pass. The boxes' resting height has a closed form: the plank's
// top plus a half, less the springs' sag (load over m_n (2 pi f)^2: under 0.5 mm for a box here and about
// 3 mm for the loaded plank). A lost or doubled constraint lets a box sink through or bounce.
TEST_CASE("a plank under 40 boxes (more constraints than colours) holds them all at rest", "[contact][colouring]") {
  auto make = [] {
    WorldSettings<2> s;
    s.gravity = -9.81 * Vec<2>::Unit(1);
    s.contact.allow_sleep = false;
    World<2> w(s);
    scenes::add_ground(w);
    BodyDef<2> plank = body_def<2>(std::make_shared<const Shape<2>>(Shape<2>::box(Vec<2>(50.0, 0.1))), 1000.0);
    plank.position = Vec<2>(0.0, 0.1);
    w.add_body(plank);
    BodyDef<2> box = body_def<2>(std::make_shared<const Shape<2>>(Shape<2>::box(Vec<2>(0.25, 0.25))), 1000.0);
    for (int i = 0; i < 40; ++i) {
      box.position = Vec<2>(-40.0 + 2.0 * i, 0.2 + 0.25);
      w.add_body(box);
    }
    return w;
  };
  World<2> w = make();
  for (int i = 0; i < 180; ++i) w.step(1.0 / 60.0);
  const double top = 0.2 + 0.25;  // the boxes' centre height on an undeformed plank
  double lowest = 1e9, highest = -1e9, fastest = 0.0;
  for (int i = 2; i < w.body_count(); ++i) {
    const Body<2>& b = w.body(BodyId{std::uint32_t(i)});
    lowest = std::min(lowest, b.center[1]);
    highest = std::max(highest, b.center[1]);
    fastest = std::max(fastest, b.velocity.norm());
  }
  INFO("box heights " << lowest << " .. " << highest << ", fastest " << fastest << " m/s");
  CHECK(w.body(BodyId{1}).center[1] > 0.1 - 5e-3);
  CHECK(lowest > top - 5e-3);
  CHECK(highest < top + 1e-3);
  CHECK(fastest < 1e-3);
  World<2> again = make();
  for (int i = 0; i < 180; ++i) again.step(1.0 / 60.0);
  CHECK(again.state_hash() == w.state_hash());
}

