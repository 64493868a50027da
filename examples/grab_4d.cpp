// A hand grabs a tesseract resting on the ground, lifts it and strikes the ground with it: the input layer
// turns the hand's poses into a grab (a soft spring solved with the contacts) and the hit into a haptic
// pulse. Built against an installed Wedge (examples/CMakeLists.txt; docs/api.md walks through it).
#include <algorithm>
#include <cstdio>
#include <memory>

#include "wedge/input/session.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

int main() {
  using namespace wedge;
  WorldSettings<4> settings;
  settings.gravity = Vec<4>(0.0, -9.81, 0.0, 0.0);  // m/s^2, y up
  World<4> world(settings);

  BodyDef<4> ground;  // the half-space y <= 0
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<4>>(Shape<4>::halfspace(Vec<4>(0.0, 1.0, 0.0, 0.0), 0.0));
  world.add_body(ground);

  const Vec<4> half = Vec<4>::Constant(0.1);                           // m: a 20 cm tesseract
  const MassProperties<4> mass = box_mass_properties<4>(half, 500.0);  // kg/m^4
  BodyDef<4> cube;
  cube.shape = std::make_shared<const Shape<4>>(Shape<4>::box(half));
  cube.mass = mass.mass;
  cube.inertia = mass.inertia;
  cube.position = Vec<4>(0.0, 0.1, 0.0, 0.0);  // resting on the ground
  world.add_body(cube);

  // The right hand, in tracking space (here the world's x, y, z at w = 0): it squeezes inside the cube,
  // lifts it to 0.5 m, strikes it down on the ground at 0.6 s and lets go at 0.9 s.
  input::Session<4> session(world, input::SessionSettings<4>{});  // 120 Hz
  while (session.time() < 1.0) {
    input::InputFrame frame;
    frame.t = session.time();
    input::HandInput& hand = frame.hands[1];
    hand.tracked = true;
    hand.squeeze = frame.t < 0.9 ? 1.0 : 0.0;
    const double y = frame.t < 0.4 ? 0.1 + frame.t : 0.5 - 2.5 * (frame.t - 0.4);
    hand.position = Eigen::Vector3d(0.0, std::max(y, 0.05), 0.0);
    session.step(frame);
  }

  for (const input::InteractionEvent<4>& e : session.events())
    std::printf("%.3f s  hand %d %s body %u\n", e.t, e.hand,
                e.kind == input::InteractionEvent<4>::Kind::Grab ? "grabs" : "lets go of", e.body.index);
  for (const input::HapticPulse<4>& p : session.pulses())
    std::printf("%.3f s  pulse to hand %d: amplitude %.2f for %.0f ms (hit at %.2f m/s)\n", p.t, p.hand,
                p.amplitude, 1000.0 * p.duration, p.approach_speed);
  std::printf("state hash %016llx\n", static_cast<unsigned long long>(world.state_hash()));
  return session.pulses().empty() ? 1 : 0;  // the strike must be felt
}
