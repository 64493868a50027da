// Collision and contact processing (core/src/contact/solver.cpp) against known physics: resting towers,
// Coulomb friction on an incline (closed form), restitution (bounce height e^2 H), conservation of
// momentum in free collisions, and energy that never rises in contact.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>

#include "wedge/scenes/builders.hpp"
#include "drift.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

constexpr double kG = 9.81;

template <int N>
WorldSettings<N> gravity_settings() {
  WorldSettings<N> s;
  s.gravity = -kG * Vec<N>::Unit(1);
  return s;
}

template <int N>
BodyDef<N> box(const Vec<N>& half, double density = 1000.0) {
  return body_def<N>(std::make_shared<const Shape<N>>(Shape<N>::box(half)), density);
}
template <int N>
BodyDef<N> ball(double radius, double density = 1000.0) {
  return body_def<N>(std::make_shared<const Shape<N>>(Shape<N>::ball(radius)), density);
}

// A box resting on the plane through the origin whose normal is turned by theta from x_1 towards x_0
// (so "down the slope" has a positive x_0 component); returns the box's id. Both materials carry mu_s
// and mu_k, so the mixed coefficients are the same (geometric mean of equal numbers).
template <int N>
BodyId incline(World<N>& w, double theta, double mu_s, double mu_k) {
  // The plane's outward normal n = -sin(theta) e0 + cos(theta) e1.
  Vec<N> n = Vec<N>::Zero();
  n[0] = -std::sin(theta);
  n[1] = std::cos(theta);
  BodyDef<N> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(n, 0.0));
  ground.material = {0.0, mu_s, mu_k};
  w.add_body(ground);
  // The rotor that turns e1 into n (checked below), so the box lies flat on the plane.
  const Rotor<N> r = exp<N>(Bivector<N>::basis(0, 1) * (-0.5 * theta));
  REQUIRE((rotate(r, Vec<N>(Vec<N>::Unit(1))) - n).norm() < 1e-12);
  const double half = 0.5;
  BodyDef<N> b = box<N>(Vec<N>::Constant(half));
  b.rotor = r;
  b.position = half * n;
  b.material = {0.0, mu_s, mu_k};
  return w.add_body(b);
}

}  // namespace

TEST_CASE("a tower of 10 tesseracts stands for 60 s: it sinks as its springs say and then no body drifts 1 mm",
          "[contact][4d]") {
  // The soft contacts are springs (drift::tower_sag): the tower settles by their compression (4.7 mm
  // here, closed form), within the first 2 s, and then stays: between 2 s and 60 s no centre moves 1 mm
  // (measured under 0.2 mm), and no centre is more than 5 mm off the tower's axis (measured 2.3-2.9 mm: the
  // sideways part of the settling).
  for (const bool sleep : {false, true}) {
    WorldSettings<4> s = gravity_settings<4>();
    s.contact.allow_sleep = sleep;
    World<4> w(s);
    scenes::add_ground(w);
    scenes::add_box_tower(w, 10);
    const double h = 1.0 / 120.0, y0 = w.bodies().back().center[1];
    for (int i = 0; i < 2 * 120; ++i) w.step(h);
    const double sag = y0 - w.bodies().back().center[1], expected = drift::tower_sag<4>(10, s.contact, h);
    const auto settled = drift::centres(w);
    double worst = 0.0, off_axis = 0.0;
    for (int i = 2 * 120; i < 60 * 120; ++i) {
      w.step(h);
      worst = std::max(worst, drift::largest(w, settled));
    }
    for (const Body<4>& b : w.bodies())
      if (b.is_dynamic()) off_axis = std::max(off_axis, (b.center - b.center[1] * Vec<4>::Unit(1)).norm());
    INFO("sleeping " << sleep << ": sag " << sag << " m (springs: " << expected << "), drift after 2 s " << worst
                     << " m, off the axis " << off_axis << " m");
    CHECK(sag == Approx(expected).epsilon(0.15));
    CHECK(worst < 1e-3);
    CHECK(off_axis < 5e-3);
    if (sleep) CHECK_FALSE(w.is_awake(BodyId{5}));
  }
}

TEMPLATE_TEST_CASE_SIG("a heavy box resting on one 100 times lighter stays still", "[contact][mass]", ((int N), N), 2,
                       3, 4) {
  // Mass ratios are where sequential impulses struggle: the light box's contacts must carry 101 times its
  // own weight. Unit boxes, densities 1000 and 10 kg/m^n, on the ground at 60 Hz, sleeping off. The
  // light box's springs compress by the spring law (below: 0.97-1.7 cm) within the first second; after
  // it nothing may move faster than 1 mm/s or drift 1 mm (measured: under 0.2 mm/s and 0.01 mm).
  // (Doubling the spring against the ground, as Box2D v3 does, made the light box chatter at 0.4 m/s in
  // 3D and 0.8 m/s in 4D; solver.cpp's paper solver rests too, to 1e-7.)
  WorldSettings<N> s = gravity_settings<N>();
  s.contact.allow_sleep = false;
  World<N> w(s);
  scenes::add_ground(w);
  BodyDef<N> light = box<N>(Vec<N>::Constant(0.5), 10.0);
  light.position = 0.5 * Vec<N>::Unit(1);
  const BodyId l = w.add_body(light);
  BodyDef<N> heavy = box<N>(Vec<N>::Constant(0.5), 1000.0);
  heavy.position = 1.5 * Vec<N>::Unit(1);
  const BodyId hv = w.add_body(heavy);
  const double h = 1.0 / 60.0, y0 = w.body(hv).center[1];
  for (int i = 0; i < 60; ++i) w.step(h);
  // Springs (drift::tower_sag's law): the top joint carries the heavy box on points of
  // 1/m_p = (1 + 1.5 (N-1)) (1/10 + 1/1000) per kg, the ground joint both boxes on the light box's.
  const double f = std::min(s.contact.contact_hertz, 0.125 * s.contact.substeps / h);
  const double k = std::pow(2.0 * M_PI * f, 2) / (1.0 + 1.5 * (N - 1)), points = 1 << (N - 1);
  const double expected = (1000.0 * 9.81 / points) / (k / (1.0 / 10 + 1.0 / 1000)) + (1010.0 * 9.81 / points) / (k * 10);
  const double sag = y0 - w.body(hv).center[1];
  const Vec<N> settled = w.body(hv).center;
  double fastest = 0.0;
  for (int i = 60; i < 600; ++i) {
    w.step(h);
    for (const BodyId id : {l, hv}) fastest = std::max(fastest, w.body(id).velocity.norm());
  }
  INFO(N << "D: sag " << sag << " m (springs: " << expected << "), fastest " << fastest << " m/s after 1 s, heavy box moved "
         << (w.body(hv).center - settled).norm() << " m");
  CHECK(sag == Approx(expected).epsilon(0.15));
  CHECK(fastest < 1e-3);
  CHECK((w.body(hv).center - settled).norm() < 1e-3);
}

TEMPLATE_TEST_CASE_SIG("a 30-box tower stands for 60 s without jitter (30 tesseracts in 4D)", "[contact][stack]",
                       ((int N), N), 2, 3, 4) {
  // Issue 15: a 30-box tower fell in 2D-4D with the paper's solver. Unit cubes at 60 Hz, sleeping off.
  // It settles by its springs' compression (drift::tower_sag: 7.8 cm in 2D, 4.3 cm in 4D) within 2 s;
  // after that no box moves faster than 5 cm/s (measured 1.1 cm/s in 2D, 2.3 cm/s in 4D: the
  // settling's sway), in the last 10 s none faster than 1 cm/s (measured 4-5 mm/s, dying out), and the
  // top stays within 3 cm of the axis (measured 0.8-2.5 cm; it would topple at 50 cm).
  WorldSettings<N> s = gravity_settings<N>();
  s.contact.allow_sleep = false;
  World<N> w(s);
  scenes::add_ground(w);
  scenes::add_box_tower(w, 30);
  const double h = 1.0 / 60.0, y0 = w.bodies().back().center[1];
  double after_settling = 0.0, last = 0.0;
  for (int i = 0; i < 60 * 60; ++i) {
    w.step(h);
    if (i == 2 * 60 - 1) {
      const double sag = y0 - w.bodies().back().center[1], expected = drift::tower_sag<N>(30, s.contact, h);
      INFO(N << "D: sag " << sag << " m, springs " << expected << " m");
      CHECK(sag == Approx(expected).epsilon(0.15));
    }
    if (i < 2 * 60) continue;
    for (const Body<N>& b : w.bodies()) {
      after_settling = std::max(after_settling, b.velocity.norm());
      if (i >= 50 * 60) last = std::max(last, b.velocity.norm());
    }
  }
  const Vec<N> top = w.bodies().back().center;
  const double off_axis = (top - top[1] * Vec<N>::Unit(1)).norm();
  INFO(N << "D: fastest after 2 s " << after_settling << " m/s, in the last 10 s " << last << " m/s, top off the axis "
         << off_axis << " m");
  CHECK(after_settling < 0.05);
  CHECK(last < 0.01);
  CHECK(off_axis < 0.03);
}

TEMPLATE_TEST_CASE_SIG("tall pyramids stand for 60 s: 100 rows in 2D, 40 rows of tesseracts in 4D",
                       "[contact][stack][slow]", ((int N), N), 2, 4) {
  // Issue 15's bar, Box2D v3's own "large pyramid" in 2D (5,050 boxes) and 820 tesseracts in 4D, at
  // 60 Hz with sleeping off: after the first 2 s no body faster than 0.5 m/s, and the top box sinks by
  // less than 0.25 m (measured: 2D 0.19 m and 0.05 m/s; 4D 0.03 m and 0.15 m/s, its top drifting 5 cm
  // sideways in the minute, docs/contact.md Known limits). Box2D v3 with its
  // defaults (4 sub-steps, 30 Hz) also stands but sinks 0.78 m; the paper's solver exploded at 100 rows.
  const int rows = N == 2 ? 100 : 40;
  WorldSettings<N> s = gravity_settings<N>();
  s.contact.allow_sleep = false;
  World<N> w(s);
  scenes::add_ground(w);
  scenes::add_box_pyramid(w, rows);
  const double y0 = w.bodies().back().center[1];
  double fastest = 0.0;
  for (int i = 0; i < 60 * 60; ++i) {
    w.step(1.0 / 60.0);
    if (i >= 2 * 60)
      for (const Body<N>& b : w.bodies()) fastest = std::max(fastest, b.velocity.norm());
  }
  const double sag = y0 - w.bodies().back().center[1];
  INFO(N << "D, " << rows << " rows: top sank " << sag << " m, fastest after 2 s " << fastest << " m/s");
  CHECK(fastest < 0.5);
  CHECK(sag < 0.25);
  CHECK(sag > 0.0);
}

TEMPLATE_TEST_CASE_SIG("a heap of boxes dropped on the ground comes to rest (64 in 2D, 100 in 3D and 4D)",
                       "[contact][friction]", ((int N), N), 2, 3, 4) {
  // Unit boxes (mu 0.6) fall from a grid, tumble and heap up. Dry friction holds such a heap in static
  // equilibrium, so once it has settled nothing may move. Bound on each body's fastest point:
  // |v| + |w| r, r = half diagonal, in the 11th and 12th second; it allows 1 mm/s. Measured: 9e-7 m/s
  // (2D), 9e-8 m/s (3D), 4e-15 m/s (4D). In 2D the grid is 8 columns of 8: 10 columns of 10 can leave a
  // column standing 10 boxes tall, whose top sways for a minute (docs/contact.md, Known limits).
  // Two solvers of the past fail it:
  //  - friction that pushed along a slip that had reversed within the step (410f1f3) kept the 3D heap
  //    at 0.12 m/s;
  //  - shock propagation that ran a level's cycling passes to the cap (117902b) kept 22 boxes of the 2D
  //    heap rocking at up to 0.46 m/s.
  const int count = N == 2 ? 64 : 100;
  const double settle = 10.0;  // s
  WorldSettings<N> s = gravity_settings<N>();
  s.contact.allow_sleep = false;  // the solver itself must bring the heap to rest
  World<N> w(s);
  scenes::add_ground(w);
  scenes::add_box_pile(w, count);
  const double r = 0.5 * std::sqrt(double(N));
  double fastest = 0.0, lowest = 1e9;
  for (int i = 0; i < int((settle + 2.0) * 60); ++i) {
    w.step(1.0 / 60.0);
    if (i < int(settle * 60)) continue;
    for (const Body<N>& b : w.bodies()) {
      if (!b.is_dynamic()) continue;
      fastest = std::max(fastest, b.velocity.norm() + b.angular_velocity.c.norm() * r);
      lowest = std::min(lowest, b.center[1]);
    }
  }
  INFO("fastest point in the last 2 s: " << fastest << " m/s; lowest centre " << lowest << " m");
  CHECK(fastest < 1e-3);
  CHECK(lowest > 0.5 - 0.01);  // nothing sinks 1 cm into the ground (the slop is 0.5 mm)
}

TEMPLATE_TEST_CASE_SIG("a box on an incline sticks up to 0.99 mu_s and beyond mu_s slides at g(sin - mu_k cos)",
                       "[contact][friction]", ((int N), N), 2, 3, 4, 5, 6) {
  const double h = 1.0 / 240.0;
  const double mu_s = 0.6, mu_k = 0.4;
  SECTION("sticks: tan(theta) = 0.5, 0.9, 0.95 and 0.99 mu_s") {
    // A box of side 1 on 2^(N-1) corners. Its uphill corners carry a quarter as much as the downhill ones
    // (the friction's moment), so they reach their cones first; friction must still hold up to the
    // cones' total. Before friction was projected onto each cone in the metric of the point's
    // tangential effective mass (solver.cpp, project_to_cone), a 4D box slid 6 m in 3 s at 0.95 mu_s and
    // a 5D one at 0.9 mu_s; 3D held to 0.95. Bound: a creep under 1 mm in 3 s where a slide with mu_k
    // would move over 4 m. 6D at 0.99 mu_s, 32 corners, is allowed 1 cm: the soft step's two passes per
    // sub-step leave its 32 coupled cones short of the last 1%, and it creeps 6.9 mm (docs/contact.md,
    // Known limits; the paper's solver with 10 passes held it to 6 um).
    for (const double ratio : {0.5, 0.9, 0.95, 0.99}) {
      WorldSettings<N> s = gravity_settings<N>();
      s.contact.allow_sleep = false;
      World<N> w(s);
      const BodyId id = incline(w, std::atan(ratio * mu_s), mu_s, mu_k);
      const Vec<N> start = w.body(id).center;
      for (int i = 0; i < 3 * 240; ++i) w.step(h);
      INFO(N << "D, tan(theta) = " << ratio << " mu_s, moved " << (w.body(id).center - start).norm() << " m in 3 s");
      CHECK((w.body(id).center - start).norm() < (N == 6 && ratio > 0.95 ? 1e-2 : 1e-3));
    }
  }
  SECTION("slides: tan(theta) = 0.7, 1.0, 1.5 > 0.6") {
    for (const double tan_theta : {0.7, 1.0, 1.5}) {
      const double theta = std::atan(tan_theta);
      WorldSettings<N> s = gravity_settings<N>();
      s.contact.allow_sleep = false;
      World<N> w(s);
      const BodyId id = incline(w, theta, mu_s, mu_k);
      const Vec<N> start = w.body(id).center;
      const double t = 2.0;
      for (int i = 0; i < int(t / h); ++i) w.step(h);
      const double expected = kG * (std::sin(theta) - mu_k * std::cos(theta));
      // Down-slope distance d = a t^2 / 2 along the slope's down direction (-cos, -sin) in (x0, x1).
      Vec<N> down = Vec<N>::Zero();
      down[0] = -std::cos(theta);
      down[1] = -std::sin(theta);
      const double d = (w.body(id).center - start).dot(down);
      const double measured = 2.0 * d / (t * t);
      INFO(N << "D, tan(theta) = " << tan_theta << ": a = " << measured << " m/s^2, expected " << expected);
      // 2% (the bound): symplectic Euler's distance sum_k k h^2 a = a t (t + h) / 2 is off by
      // h/(2t) = 0.1%; the box starts at rest, so it holds with mu_s until it slips faster than
      // static_slip_speed (1 cm/s, a few ms), which costs well under 1% of the distance in 2 s.
      CHECK(measured == Approx(expected).epsilon(0.02));
      // It slides straight down: sideways drift under 1% of the distance slid, and no more than a slow turn.
      const Vec<N> moved = w.body(id).center - start;
      CHECK(moved.tail(N - 2).norm() < 0.01 * d);
      CHECK(w.body(id).angular_velocity.c.norm() < 0.05);
    }
  }
}

TEMPLATE_TEST_CASE_SIG("a ball dropped on the ground bounces to e^2 of its height", "[contact][restitution]",
                       ((int N), N), 2, 3, 4, 5) {
  const double h = 1.0 / 2000.0, drop = 1.0, radius = 0.25;
  for (const double e : {0.5, 0.8}) {
    WorldSettings<N> s = gravity_settings<N>();
    s.contact.allow_sleep = false;
    World<N> w(s);
    scenes::add_ground(w);
    BodyDef<N> def = ball<N>(radius);
    def.position[1] = radius + drop;
    def.material.restitution = e;
    const BodyId id = w.add_body(def);
    // Fall, bounce, then record the highest point until it comes down again.
    bool bounced = false;
    double apex = 0.0;
    for (int i = 0; i < int(2.0 / h); ++i) {
      w.step(h);
      const double v = w.body(id).velocity[1], y = w.body(id).center[1] - radius;
      if (!bounced && v > 0.0) bounced = true;
      if (bounced) apex = std::max(apex, y);
      if (bounced && v < 0.0 && y < 0.5 * apex) break;
    }
    REQUIRE(bounced);
    // The bounce happens in the step in which the gap would close, up to h v_impact = 2.2 mm above the
    // ground; the rebound then starts that high, with speed e v at that height, so the apex lies within
    // h v_impact (1 + e^2) of e^2 H, about 0.3% of e^2 H for e = 0.8 and 1.1% for e = 0.5.
    const double v_impact = std::sqrt(2.0 * kG * drop);
    INFO("N = " << N << ", e = " << e << ": apex " << apex << " m, e^2 H = " << e * e * drop);
    CHECK(std::abs(apex - e * e * drop) <= h * v_impact * (1.0 + e * e) + 1e-6);
  }
}

TEMPLATE_TEST_CASE_SIG("free collisions conserve linear and angular momentum and never gain energy",
                       "[contact][conservation]", ((int N), N), 2, 3, 4, 5) {
  // Two cubes thrown at each other off-centre with spin, no gravity, with friction and restitution 0,
  // 0.5 or 1. Cubes, because their inertia is isotropic: free flight then conserves L exactly (no
  // gyroscopic drift from the integrator), so any change of L is the contact's.
  for (const ContactSolver solver : {ContactSolver::Paper, ContactSolver::SoftStep})
    for (const double e : {0.0, 0.5, 1.0}) {
      // Paper: split-impulse position correction moves bodies apart without momentum, which changes the
      // angular momentum about the origin by sum m dx ^ v; it is kept out of the way here (slop 1 m) so
      // that the impulses alone are tested. The second world runs with the defaults and bounds that.
      WorldSettings<N> settings;
      settings.contact.solver = solver;
      settings.contact.linear_slop = 1.0;
      World<N> w(settings);
      BodyDef<N> a = box<N>(Vec<N>::Constant(0.45));
      a.position[0] = -1.0;
      a.velocity[0] = 2.0;
      a.angular_velocity.c.setConstant(0.7);
      a.material = {e, 0.8, 0.6};
      BodyDef<N> b = box<N>(Vec<N>::Constant(0.4), 500.0);
      b.position[0] = 1.0;
      b.position[1] = 0.25;
      b.velocity[0] = -1.5;
      b.rotor = exp<N>(Bivector<N>::basis(0, 1) * 0.3);
      b.material = {e, 0.8, 0.6};
      w.add_body(a);
      w.add_body(b);
      const Vec<N> p0 = w.linear_momentum();
      const Bivector<N> l0 = w.angular_momentum();
      const double e0 = w.kinetic_energy();
      bool collided = false;
      WorldSettings<N> defaults;
      defaults.contact.solver = solver;
      World<N> corrected(defaults);
      corrected.add_body(a);
      corrected.add_body(b);
      double energy = e0, worst_rise = 0.0, impulse = 0.0, corrected_impulse = 0.0;
      const double h = 1.0 / 120.0;
      for (int i = 0; i < 240; ++i) {
        w.step(h);
        corrected.step(h);
        collided = collided || !w.contact_begin_events().empty();
        worst_rise = std::max(worst_rise, w.kinetic_energy() - energy);
        energy = w.kinetic_energy();
        for (const ContactInfo<N>& c : w.contacts())
          for (int k = 0; k < c.manifold.count; ++k) impulse += c.normal_impulse[k];
        for (const ContactInfo<N>& c : corrected.contacts())
          for (int k = 0; k < c.manifold.count; ++k) corrected_impulse += c.normal_impulse[k];
      }
      REQUIRE(collided);
      const bool paper = solver == ContactSolver::Paper;
      INFO("N = " << N << ", e = " << e << (paper ? ", paper" : ", soft step") << ": kinetic energy " << e0
                  << " -> " << w.kinetic_energy());
      // Impulses are equal and opposite, so momentum changes only by round-off (1e-12 of |p| = 2.6 kg m/s
      // ... scaled by the masses).
      CHECK((w.linear_momentum() - p0).norm() <= 1e-9 * p0.norm());
      const double dl = (w.angular_momentum() - l0).c.norm();
      const double v_rel = 2.0 * 3.5, mu = 0.8;
      if (paper) {
        // The paper's impulses act at one point of both bodies, which stand still while they are solved:
        // L is conserved to round-off.
        CHECK(dl <= 1e-9 * (l0.c.norm() + p0.norm()));
      } else {
        // The soft step applies each point's impulses at lever arms fixed when the step began while the
        // sub-steps move the bodies, so the two application points part by at most the relative
        // displacement within a step, |v_rel| h (3.5 m/s closing, spin included below 2 |v_rel|): L may
        // change by at most the total normal and friction impulse times that.
        INFO("|dL| = " << dl << ", total normal impulse " << impulse << " N s");
        CHECK(dl <= (1.0 + mu) * impulse * v_rel * h);
      }
      INFO("largest rise in one step " << worst_rise << " J");
      // Energy never rises in any step (round-off: 1e-9 of it).
      CHECK(worst_rise <= 1e-9 * e0);
      if (e < 1.0) CHECK(w.kinetic_energy() < e0);
      // With the defaults linear momentum is still exact; L moves by less than 1e-3 of its size (paper: the
      // bodies overlap by under a millimetre while they roll against each other) or within the soft
      // step's bound above.
      CHECK((corrected.linear_momentum() - p0).norm() <= 1e-9 * p0.norm());
      const double corrected_dl = (corrected.angular_momentum() - l0).c.norm();
      if (paper)
        CHECK(corrected_dl <= 1e-3 * (l0.c.norm() + p0.norm()));
      else
        CHECK(corrected_dl <= (1.0 + mu) * corrected_impulse * v_rel * h);
    }
}

TEST_CASE("kinetic energy never rises while 40 bodies collide in a closed 4D room", "[contact][energy][4d]") {
  // No gravity, so the kinetic energy is all the energy; every step may only lower it (up to round-off).
  // Tesseracts and 4-balls with random velocities, spins and restitutions 0..0.9 bounce off each other
  // and off the 8 walls (half-spaces) of a 6 m room, with friction 0.5/0.4.
  World<4> w;
  for (int axis = 0; axis < 4; ++axis)
    for (const double side : {-1.0, 1.0}) {
      BodyDef<4> wall;
      wall.type = BodyType::Static;
      wall.shape = std::make_shared<const Shape<4>>(Shape<4>::halfspace(Vec<4>(-side * Vec<4>::Unit(axis)), -3.0));
      w.add_body(wall);
    }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e01(0.0, 0.9);
  for (int i = 0; i < 40; ++i) {
    BodyDef<4> b = i % 3 == 0 ? ball<4>(0.3) : box<4>(Vec<4>(0.3, 0.25, 0.2, 0.35));
    b.position = Vec<4>(-2.0 + 1.3 * (i % 4), -2.0 + 1.3 * ((i / 4) % 4), -1.5 + 1.5 * ((i / 16) % 3), 0.0);
    for (int k = 0; k < 4; ++k) b.velocity[k] = 3.0 * u(rng);
    for (int k = 0; k < 6; ++k) b.angular_velocity.c[k] = 2.0 * u(rng);
    b.material.restitution = e01(rng);
    w.add_body(b);
  }
  double energy = w.kinetic_energy(), worst_rise = 0.0;
  const double start = energy;
  int begins = 0;
  for (int i = 0; i < 4 * 120; ++i) {
    w.step(1.0 / 120.0);
    begins += int(w.contact_begin_events().size());
    worst_rise = std::max(worst_rise, w.kinetic_energy() - energy);
    energy = w.kinetic_energy();
  }
  INFO(begins << " contacts began; kinetic energy " << start << " -> " << energy << " J; largest rise in one step "
              << worst_rise << " J");
  CHECK(begins > 100);
  // The box bodies are not isotropic, so their free rotation alone moves the kinetic energy by the
  // implicit midpoint's round-off (1e-12 relative per step, see test_world.cpp): allow 1e-9 of it.
  CHECK(worst_rise <= 1e-9 * start);
  CHECK(energy < 0.9 * start);
}
