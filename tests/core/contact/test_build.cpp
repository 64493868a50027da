// The constraint build (core/src/contact/build.cpp): the effective masses a recycled pair takes from the
// last step against those formed afresh; the soft step's lanes, built straight from the pairs, against
// those packed from points formed afresh; the materials' mixing.
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

TEMPLATE_TEST_CASE_SIG("a recycled pair's effective masses are those formed afresh, to the bit (2D-4D)",
                       "[contact][recycling]", ((int N), N), 2, 3, 4) {
  // Straight on the contact pipeline: a ground, two cubes stacked (isotropic inertia) and a cuboid
  // (not, from 3D on), nudged below the recycling limits between calls of find_contacts, so their
  // manifolds are recycled. Every point's effective masses and Jacobian rows, copied from the last step
  // or formed, must equal the bits build_constraint's formulas give from this step's bodies; once a
  // cube's mass changes, and whenever the cuboid turns, that takes forming them again. (Recycling is
  // the soft step's. It builds its points straight into the lanes, and keeps the masses in
  // point_masses, the tangent mass in 2D along t alone; "the lanes are those packed from points" checks
  // that the lanes take them.)
  ContactBodies<N> scene;
  std::vector<Body<N>>& bodies = scene.bodies;
  scene.add_ground();
  const auto cube = std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(0.5)));
  scene.add(cube, BodyType::Dynamic, 0.499 * Vec<N>::Unit(1));
  scene.add(cube, BodyType::Dynamic, 1.497 * Vec<N>::Unit(1));
  Vec<N> half = Vec<N>::Constant(0.4);
  half[0] = 0.7;
  half[1] = 0.3;
  scene.add(std::make_shared<const Shape<N>>(Shape<N>::box(half)), BodyType::Dynamic,
      Vec<N>(3.0 * Vec<N>::Unit(0) + 0.299 * Vec<N>::Unit(1)));
  const bool cuboid_isotropic = N == 2;  // (in 2D every inertia is a single number)

  contact::ContactState<N> s;
  for (int i = 0; i < int(bodies.size()); ++i) contact::add_body(s, bodies, scene.shapes, i);
  const ContactSettings settings;
  REQUIRE(settings.solver == ContactSolver::SoftStep);
  int eligible_count = 0;  // cube pairs whose masses may be copied (recycled, isotropic bodies)
  for (int round = 0; round < 12; ++round) {
    contact::find_contacts(s, bodies, scene.shapes, scene.materials, settings, 1.0 / 60.0);
    REQUIRE(s.graph.constraints.size() == 3);  // ground-cube, cube-cube, ground-cuboid
    for (const contact::Constraint<N>& c : s.graph.constraints) {
      const contact::Pair<N>& p = s.list.pairs[c.pair];
      const contact::BodyMass<N>& a = s.masses[c.a];
      const contact::BodyMass<N>& b = s.masses[c.b];
      // (Every round builds the same three pairs, so each was built in the last one from round 1.)
      const bool eligible = p.recycled && round > 0 && a.isotropic && b.isotropic;
      CHECK(p.built == s.graph.builds);  // (this build's number, which tells the next build where they were)
      CHECK(p.points_first == c.first);
      if (round > 0) CHECK(p.recycled);  // nudges below the limits
      if (c.b == 3) {
        CHECK(eligible == (round > 0 && cuboid_isotropic));  // the turned cuboid's inertia turns with it
      } else if (eligible) {
        ++eligible_count;
      }
      for (int k = 0; k < c.count; ++k) {
        contact::PointConstraint<N> e;
        contact::set_effective_masses(e,
                                      Mat<N>((a.inv_mass + b.inv_mass) * Mat<N>::Identity() +
                                             contact::angular_mass_term(a, p.arm_a[k]) +
                                             contact::angular_mass_term(b, p.arm_b[k])),
                                      c.normal);
        const auto jn_a = outer<N>(p.arm_a[k], c.normal).c, jn_b = outer<N>(p.arm_b[k], c.normal).c;
        const contact::PointMasses<N>& q = s.soft.point_masses[c.first + k];
        REQUIRE(q.normal_mass == e.normal_mass);
        if constexpr (N == 2) {
          const Vec<2> t(-c.normal[1], c.normal[0]);
          REQUIRE(q.tangent_mass == t.dot(e.tangent_mass * t));
        } else {
          REQUIRE(q.tangent_mass == e.tangent_mass);
        }
        REQUIRE(q.jn_a == jn_a);
        REQUIRE(q.jn_b == jn_b);
      }
      if (c.a == 0 && c.b == 1) {
        // The closed form at the cube's ground corners: the ground does not move, the cube's inverse
        // inertia is 6/m in every plane (I = m (a_i^2 + a_j^2) / 3 with a = 1/2) and each corner's arm
        // has tangential part (+-1/2, ..): 1/m_n = 1/m + (6/m)(|r|^2 - (r.n)^2) = (1 + 3(N - 1)/2)/m.
        // From round 6 the cube weighs twice as much (had the last step's masses been copied over the
        // change, this and the bit checks above would fail). Agreement to round-off.
        const double m = round <= 5 ? 1000.0 : 2000.0;  // kg: 1000 kg/m^N times the unit cube
        for (int k = 0; k < c.count; ++k)
          CHECK(s.soft.point_masses[c.first + k].normal_mass == Approx(m / (1.0 + 1.5 * (N - 1))).epsilon(1e-12));
      }
    }
    // The nudges, each well below recycle_distance (5 cm) and recycle_angle (0.2 rad).
    bodies[2].center[0] += 1e-4;
    Bivector<N> turn{};
    turn.c[0] = 1e-3;  // e01
    bodies[3].rotor = wedge::exp(turn) * bodies[3].rotor;
    if (round == 5) {
      bodies[1].mass *= 2.0;
      bodies[1].inv_mass *= 0.5;
      bodies[1].inv_inertia *= 0.5;
    }
  }
  // Both cube pairs (ground-cube, cube-cube) in rounds 1-11: the path under test ran.
  CHECK(eligible_count == 22);
}

// find_contacts builds the soft step's points straight into the lanes (build_wide), never as
// PointConstraints. Here every point is formed again as a PointConstraint from its pair, bodies and
// constraint by the formulas of paper section 6 (lever arms, K, jn = r ^ n, I^-1 jn, approach and slip
// from the bodies' velocities), prepared (prepare_points) and packed by fill_wide, the reference
// packing; the lanes must be those bytes exactly, header, slots, inertias and approach speeds. Three
// rounds with nudges below the recycling limits and a sub-step's passes between them, so the recycled
// pairs' copied masses are checked too, and the lanes kept from the round before (graph_kept); the last
// round collides every pair afresh under the kept graph.
// The scene fills lanes unevenly: a row of cubes on the ground, a stack, a cuboid (not isotropic from
// 3D on: wide inertias) and a cube on an edge (2^(N-2) points beside 2^(N-1)), all moving.
// (Without warm start: the warm matching is the same code for both solvers.)
TEMPLATE_TEST_CASE_SIG("the soft step's lanes are those packed from points formed afresh, to the bit (2D-4D)",
                       "[contact][lanes]", ((int N), N), 2, 3, 4) {
  ContactBodies<N> scene;
  std::vector<Body<N>>& bodies = scene.bodies;
  scene.add_ground();
  const auto cube = std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(0.5)));
  // (10 on the ground: a colour fills the 8 lanes of a 2D wide constraint, whose lanes may be kept.)
  for (int i = 0; i < 10; ++i) scene.add(cube, BodyType::Dynamic, Vec<N>(1.5 * i * Vec<N>::Unit(0) + 0.499 * Vec<N>::Unit(1)));
  scene.add(cube, BodyType::Dynamic, Vec<N>(0.2 * Vec<N>::Unit(0) + 1.497 * Vec<N>::Unit(1)));
  Vec<N> half = Vec<N>::Constant(0.4);
  half[0] = 0.7;
  half[1] = 0.3;
  scene.add(std::make_shared<const Shape<N>>(Shape<N>::box(half)), BodyType::Dynamic,
            Vec<N>(-3.0 * Vec<N>::Unit(0) + 0.299 * Vec<N>::Unit(1)));
  {  // a cube turned in the e01 plane, its lowest edge 1 mm into the ground
    const int i = scene.add(cube, BodyType::Dynamic, Vec<N>(-6.0 * Vec<N>::Unit(0)));
    Bivector<N> turn{};
    turn.c[0] = 0.2;
    bodies[i].rotor = wedge::exp(turn);
    const Mat<N> r = to_matrix(bodies[i].rotor);
    double lowest = 0.0;
    for (int corner = 0; corner < (1 << N); ++corner) {
      Vec<N> x;
      for (int j = 0; j < N; ++j) x[j] = (corner >> j & 1) ? 0.5 : -0.5;
      lowest = std::min(lowest, Vec<N>(r * x)[1]);
    }
    bodies[i].center[1] = -lowest - 1e-3;
  }
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    bodies[i].velocity = Vec<N>::Zero();
    bodies[i].velocity[0] = 0.04 * double(i % 3) - 0.03;
    bodies[i].velocity[1] = -0.05;
    bodies[i].angular_velocity.c[0] = 0.03 - 0.02 * double(i % 4);
  }
  contact::ContactState<N> s;
  for (int i = 0; i < int(bodies.size()); ++i) contact::add_body(s, bodies, scene.shapes, i);
  ContactSettings settings;
  settings.warm_start = false;
  int recycled = 0, inertias = 0, padded = 0, sliding = 0, kept = 0, kept_whole = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {  // (mixed materials: each pair mixes its own)
    scene.materials[i].friction = 0.3 + 0.05 * double(i);
    scene.materials[i].kinetic_friction = 0.25 + 0.04 * double(i);
    scene.materials[i].restitution = 0.1 * double(i % 3);
  }
  for (int round = 0; round < 3; ++round) {
    INFO("round " << round);
    // (Round 2 collides every pair afresh, with the ground turned by 1e-5 rad: the graph is kept, the
    // ground's normals are new, the masses are formed again.)
    settings.recycle_distance = round == 2 ? 0.0 : ContactSettings{}.recycle_distance;
    if (round == 2) {
      Bivector<N> tilt{};
      tilt.c[0] = 1e-5;
      bodies[0].rotor = wedge::exp(tilt);
    }
    contact::find_contacts(s, bodies, scene.shapes, scene.materials, settings, 1.0 / 60.0);
    REQUIRE(s.graph.constraints.size() == 13);  // 12 on the ground, 1 in the stack
    contact::ContactState<N> ref = s;
    ref.paper.points.clear();
    for (const contact::Constraint<N>& c : ref.graph.constraints) {
      const contact::Pair<N>& p = ref.list.pairs[c.pair];
      recycled += p.recycled;
      // The constraint as its pair and its bodies' materials make it, kept from the last round or not.
      const Material& ma = scene.materials[c.a];
      const Material& mb = scene.materials[c.b];
      CHECK((c.a == int(p.a) && c.b == int(p.b) && c.count == p.manifold.count));
      CHECK(c.normal == p.manifold.normal);
      CHECK(c.friction == mix_friction(ma.friction, mb.friction));
      CHECK(c.kinetic_friction == std::min(mix_friction(ma.kinetic_friction, mb.kinetic_friction), c.friction));
      CHECK(c.restitution == mix_restitution(ma.restitution, mb.restitution));
      const contact::BodyMass<N>& a = ref.masses[c.a];
      const contact::BodyMass<N>& b = ref.masses[c.b];
      REQUIRE(c.first == int(ref.paper.points.size()));
      for (int k = 0; k < c.count; ++k) {
        contact::PointConstraint<N> q;
        q.ra = p.arm_a[k];
        q.rb = p.arm_b[k];
        contact::set_effective_masses(q,
                                      Mat<N>((a.inv_mass + b.inv_mass) * Mat<N>::Identity() +
                                             contact::angular_mass_term(a, q.ra) + contact::angular_mass_term(b, q.rb)),
                                      c.normal);
        q.jn_a = outer<N>(q.ra, c.normal).c;
        q.jn_b = outer<N>(q.rb, c.normal).c;
        q.dn_a = contact::inverse_inertia_times(a, q.jn_a);
        q.dn_b = contact::inverse_inertia_times(b, q.jn_b);
        q.gap = -p.manifold.points[k].depth;
        const contact::SolverBody<N>& va = ref.solver_bodies[c.a];
        const contact::SolverBody<N>& vb = ref.solver_bodies[c.b];
        const Vec<N> u = vb.v + dot<N>(q.rb, vb.w) - va.v - dot<N>(q.ra, va.w);
        q.approach = c.normal.dot(u);
        const Vec<N> slip = u - q.approach * c.normal;
        q.sliding = slip.norm() > settings.static_slip_speed;
        if (q.sliding) q.slip_direction = slip / slip.norm();
        sliding += q.sliding;
        q.friction = q.sliding ? c.kinetic_friction : c.friction;
        ref.paper.points.push_back(q);
      }
      contact::prepare_points(ref, c, false);
    }
    for (contact::WideConstraint<N>& w : ref.soft.wide) {
      contact::fill_wide(ref, w);
      inertias += w.inertia >= 0;
      for (int l = 0; l < contact::kLanes<N>; ++l)
        padded += w.constraint[l] >= 0 && ref.graph.constraints[w.constraint[l]].count < w.count;
    }
    const auto same = [](const auto& x, const auto& y) {
      return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
    };
    REQUIRE(same(s.soft.wide, ref.soft.wide));
    CHECK(same(s.soft.wide_points, ref.soft.wide_points));
    CHECK(same(s.soft.wide_cold, ref.soft.wide_cold));
    CHECK(same(s.soft.wide_approach, ref.soft.wide_approach));
    CHECK(same(s.soft.wide_inertia, ref.soft.wide_inertia));
    kept += s.graph.graph_kept;
    // Where the lanes were kept whole: a full wide constraint of isotropic bodies, all its pairs recycled.
    for (const contact::WideConstraint<N>& w : s.soft.wide) {
      bool whole = s.graph.graph_kept && w.inertia < 0;
      for (int l = 0; l < contact::kLanes<N>; ++l)
        whole = whole && w.constraint[l] >= 0 && s.list.pairs[s.graph.constraints[w.constraint[l]].pair].recycled;
      kept_whole += whole;
    }
    // A sub-step's passes between rounds: they write the lanes' impulses and separations, which the
    // next round's kept lanes must write over (and they change the velocities the points start from).
    contact::prepare_soft_step(s, bodies, settings, 1.0 / 60.0);
    contact::solve_substep(s, bodies, settings, 1.0 / 240.0, true);
    contact::solve_substep(s, bodies, settings, 1.0 / 240.0, false);
    contact::finish_soft_step(s, bodies, settings);
    // The nudges, well below recycle_distance (5 cm) and recycle_angle (0.2 rad).
    for (std::size_t i = 1; i < bodies.size(); ++i) bodies[i].center[0] += 1e-4;
  }
  // Rounds 1 and 2 find the same constraints as the round before: the lanes are kept, and the
  // recycled pairs' masses are not written again (build_wide).
  CHECK(kept == 2);
  CHECK(kept_whole > 0);
  CHECK(recycled > 0);
  CHECK(padded > 0);
  CHECK(sliding > 0);
  CHECK((inertias > 0) == (N > 2));
}

TEST_CASE("equal friction coefficients mix to themselves, as sqrt(a a) does, to the bit", "[contact]") {
  // Oracle: the geometric mean from the library's sqrt, on log-spaced coefficients from 1e-150 to 1e150
  // (inside the shortcut's range, 2^-500 to 2^500, everyday values included) and on unequal pairs,
  // which take the square root as before.
  int equal = 0;
  for (double a = 1e-150; a < 1e150; a *= 1.37) {
    INFO("a = " << a);
    CHECK(mix_friction(a, a) == std::sqrt(a * a));
    CHECK(mix_friction(a, 0.6) == std::sqrt(a * 0.6));
    ++equal;
  }
  CHECK(mix_friction(0.0, 0.0) == 0.0);
  CHECK(mix_friction(0.6, 0.6) == 0.6);
  CHECK(equal > 2000);
}
