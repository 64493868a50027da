// World queries and the World API the input layer needs (core/src/world_queries.cpp, world.cpp):
//   - query_point against brute force over every body (point_query per shape, the lowest index on ties);
//   - ray_cast against closed forms: a ray hits a ball at t = b - sqrt(b^2 - c) and a box where the slab
//     intervals first all overlap; tolerance 1e-8 m (sphere tracing stops within 1e-12 m of the surface,
//     and the box distance is exact);
//   - set_gravity wakes sleeping bodies and refuses non-finite vectors; user data; checked ids;
//   - time is accumulated: 600 steps of 1/120 s are 5 s exactly, mixed steps sum.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "test_util.hpp"
#include "wedge/collision/point_query.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;

namespace {

template <int N>
BodyDef<N> body(Shape<N> shape, const Vec<N>& at, BodyType type = BodyType::Dynamic) {
  BodyDef<N> d;
  d.type = type;
  d.position = at;
  d.shape = std::make_shared<const Shape<N>>(std::move(shape));
  if (d.shape->bounded()) {
    const MassProperties<N> mp = mass_properties(*d.shape, 1000.0);
    d.mass = mp.mass;
    d.inertia = mp.inertia;
    d.local_center = mp.center;
  }
  return d;
}

// A world of balls and boxes scattered at random in [-2, 2]^N, and their closed-form descriptions.
template <int N>
struct Scatter {
  World<N> world;
  std::vector<Vec<N>> centers;
  std::vector<double> radius;        // > 0: a ball
  std::vector<Vec<N>> half_extents;  // axis-aligned box when radius == 0
  explicit Scatter(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-2.0, 2.0), s(0.1, 0.5);
    for (int i = 0; i < 12; ++i) {
      const Vec<N> c = Vec<N>::NullaryExpr([&] { return u(rng); });
      if (i % 2 == 0) {
        const double r = s(rng);
        world.add_body(body<N>(Shape<N>::ball(r), c, i % 4 == 0 ? BodyType::Static : BodyType::Dynamic));
        radius.push_back(r);
        half_extents.push_back(Vec<N>::Zero());
      } else {
        const Vec<N> he = Vec<N>::NullaryExpr([&] { return s(rng); });
        world.add_body(body<N>(Shape<N>::box(he), c));
        radius.push_back(0.0);
        half_extents.push_back(he);
      }
      centers.push_back(c);
    }
  }
  // Closed-form ray parameter of body i, or infinity.
  double ray(int i, const Vec<N>& o, const Vec<N>& d) const {
    const Vec<N> rel = o - centers[i];
    if (radius[i] > 0.0) {
      const double b = -rel.dot(d), c = rel.squaredNorm() - radius[i] * radius[i];
      if (c <= 0.0) return 0.0;
      const double disc = b * b - c;
      if (disc < 0.0 || b < 0.0) return INFINITY;
      return b - std::sqrt(disc);
    }
    double lo = 0.0, hi = INFINITY;
    for (int k = 0; k < N; ++k) {
      if (d[k] == 0.0) {
        if (std::abs(rel[k]) > half_extents[i][k]) return INFINITY;
        continue;
      }
      double t1 = (-half_extents[i][k] - rel[k]) / d[k], t2 = (half_extents[i][k] - rel[k]) / d[k];
      if (t1 > t2) std::swap(t1, t2);
      lo = std::max(lo, t1);
      hi = std::min(hi, t2);
    }
    return lo <= hi ? lo : INFINITY;
  }
};

}  // namespace

TEMPLATE_TEST_CASE("query_point agrees with brute force over every body", "[world][queries]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(7 + N);
  Scatter<N> sc(rng);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  int inside = 0, near = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // About a body's centre, so that both answers come up in 6D too (random points in [-2.5, 2.5]^6 miss).
    const Vec<N> x = sc.centers[trial % sc.centers.size()] + Vec<N>::NullaryExpr([&] { return u(rng); });
    for (bool with_static : {true, false}) {
      // Brute force: the lowest-index body containing x, else the nearest within 0.3 m.
      int best = -1;
      double best_d = INFINITY;
      bool best_in = false;
      for (int i = 0; i < sc.world.body_count(); ++i) {
        const BodyId id{std::uint32_t(i)};
        if (!with_static && sc.world.body(id).type == BodyType::Static) continue;
        const Body<N>& b = sc.world.body(id);
        const PointQuery<N> q = point_query(*sc.world.shape(id), Transform<N>{b.position(), to_matrix(b.rotor)}, x);
        if (q.inside && !best_in) {
          best = i, best_d = 0.0, best_in = true;
        } else if (!best_in && !q.inside && q.distance <= 0.3 && q.distance < best_d) {
          best = i, best_d = q.distance;
        }
      }
      const auto hit = sc.world.query_point(x, 0.3, with_static);
      REQUIRE(hit.has_value() == (best >= 0));
      if (!hit) continue;
      CHECK(int(hit->body.index) == best);
      CHECK(hit->inside == best_in);
      CHECK(hit->distance == Approx(best_d).margin(1e-12));
      inside += best_in;
      near += !best_in;
    }
  }
  CHECK(inside > 20);  // both branches exercised
  CHECK(near > 20);
}

TEMPLATE_TEST_CASE("ray_cast agrees with the closed forms for balls and boxes", "[world][queries]", D2, D3, D4, D5,
                   D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(11 + N);
  Scatter<N> sc(rng);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::normal_distribution<double> nd;
  int hits = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec<N> o = Vec<N>::NullaryExpr([&] { return u(rng); });
    // Half the rays aim at a body's centre (so many hit), half go anywhere.
    Vec<N> d = trial % 2 ? Vec<N>(sc.centers[trial % sc.centers.size()] - o) : Vec<N>::NullaryExpr([&] { return nd(rng); });
    d.normalize();
    double truth = INFINITY;
    int who = -1;
    for (int i = 0; i < int(sc.centers.size()); ++i) {
      const double t = sc.ray(i, o, d);
      if (t <= 6.0 && t < truth) truth = t, who = i;
    }
    const auto hit = sc.world.ray_cast(o, 2.0 * d, 6.0);  // (direction need not be unit)
    REQUIRE(hit.has_value() == (who >= 0));
    if (!hit) continue;
    ++hits;
    CHECK(int(hit->body.index) == who);
    CHECK(hit->distance == Approx(truth).margin(1e-8));
    CHECK((hit->point - (o + truth * d)).norm() < 1e-8);
    CHECK(hit->normal.norm() == Approx(1.0).margin(1e-9));
    if (truth > 0.0) CHECK(hit->normal.dot(d) < 1e-9);  // facing the ray
  }
  CHECK(hits > 100);
}

TEST_CASE("ray_cast hits a half-space ground and respects max_distance and include_static", "[world][queries]") {
  World<4> world;
  BodyDef<4> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<4>>(Shape<4>::halfspace(Vec<4>(0, 1, 0, 0), 0.0));
  world.add_body(ground);
  const Vec<4> o(0, 2, 0, 0), d = Vec<4>(1, -1, 0, 0).normalized();
  const auto hit = world.ray_cast(o, d, 10.0);
  REQUIRE(hit);
  CHECK(hit->distance == Approx(2.0 * std::sqrt(2.0)).margin(1e-8));
  CHECK((hit->normal - Vec<4>(0, 1, 0, 0)).norm() < 1e-6);
  CHECK_FALSE(world.ray_cast(o, d, 2.8));
  CHECK_FALSE(world.ray_cast(o, d, 10.0, false));
  CHECK_THROWS(world.ray_cast(o, Vec<4>::Zero(), 1.0));
}

namespace {

// A 20 cm box (body 1) on the ground under gravity -9.81 m/s^2 along y, asleep after 2 s at rest.
World<3> box_asleep_on_ground() {
  WorldSettings<3> s;
  s.gravity = Vec<3>(0, -9.81, 0);
  World<3> world(s);
  BodyDef<3> ground;
  ground.type = BodyType::Static;
  ground.shape = std::make_shared<const Shape<3>>(Shape<3>::halfspace(Vec<3>(0, 1, 0), 0.0));
  world.add_body(ground);
  world.add_body(body<3>(Shape<3>::box(Vec<3>::Constant(0.1)), Vec<3>(0, 0.1, 0)));
  for (int i = 0; i < 240; ++i) world.step(1.0 / 120.0);
  return world;
}

}  // namespace

TEST_CASE("set_gravity wakes sleeping bodies and refuses non-finite vectors", "[world]") {
  World<3> world = box_asleep_on_ground();
  const BodyId box{1};
  REQUIRE_FALSE(world.is_awake(box));
  CHECK_THROWS_WITH(world.set_gravity(Vec<3>(NAN, 0, 0)), Catch::Contains("finite"));
  world.set_gravity(Vec<3>(0, -9.81, 0));  // unchanged: stays asleep
  CHECK_FALSE(world.is_awake(box));
  world.set_gravity(Vec<3>(0, 9.81, 0));  // gravity reversed: it must fall up
  CHECK(world.is_awake(box));
  for (int i = 0; i < 60; ++i) world.step(1.0 / 120.0);
  CHECK(world.body(box).center[1] > 0.1 + 0.5 * 9.81 * 0.25 - 0.05);  // free fall upward for 0.5 s
}

TEST_CASE("set_settings checks what it is given, leaves the world unchanged on refusal, wakes on new gravity",
          "[world]") {
  World<3> world = box_asleep_on_ground();
  const BodyId box{1};
  REQUIRE_FALSE(world.is_awake(box));
  // Each refusal names the field and changes nothing, the other fields of the same call included.
  CHECK_THROWS_WITH(world.update_settings([](auto& ws) { ws.contact.substeps = 0; }), Catch::Contains("substeps"));
  CHECK_THROWS_WITH(world.update_settings([](auto& ws) {
                      ws.gravity = Vec<3>(0, 9.81, 0);
                      ws.contact.contact_margin = -1.0;
                    }),
                    Catch::Contains("contact_margin"));
  CHECK_THROWS_WITH(world.update_settings([](auto& ws) { ws.gravity[0] = INFINITY; }), Catch::Contains("gravity"));
  CHECK(world.settings().gravity == Vec<3>(0, -9.81, 0));
  CHECK(world.settings().contact.substeps == WorldSettings<3>{}.contact.substeps);
  CHECK_FALSE(world.is_awake(box));
  // Accepted: the new substeps hold, and gravity turned upward wakes the box, which falls up.
  world.update_settings([](auto& ws) {
    ws.contact.substeps = 2;
    ws.gravity = Vec<3>(0, 9.81, 0);
  });
  CHECK(world.settings().contact.substeps == 2);
  CHECK(world.is_awake(box));
  for (int i = 0; i < 60; ++i) world.step(1.0 / 120.0);
  CHECK(world.body(box).center[1] > 0.1 + 0.5 * 9.81 * 0.25 - 0.05);  // free fall upward for 0.5 s
}

TEST_CASE("user data, checked ids and accumulated time", "[world]") {
  World<2> world;
  BodyDef<2> d = body<2>(Shape<2>::ball(0.5), Vec<2>::Zero());
  d.user_data = 42;
  const BodyId id = world.add_body(d);
  CHECK(world.user_data(id) == 42);
  world.set_user_data(id, 0xdeadbeefULL);
  CHECK(world.user_data(id) == 0xdeadbeefULL);
  CHECK_THROWS_WITH(world.body(BodyId{1}), Catch::Contains("body id 1") && Catch::Contains("it has 1"));
  CHECK_THROWS(world.apply_force(BodyId{3}, Vec<2>::Zero()));
  CHECK_THROWS_WITH(world.apply_force(id, Vec<2>(INFINITY, 0)), Catch::Contains("non-finite"));
  for (int i = 0; i < 600; ++i) world.step(1.0 / 120.0);
  CHECK(world.time() == 5.0);  // compensated sum: exactly
  world.step(0.001);
  world.step(0.002);
  CHECK(world.time() == Approx(5.003).epsilon(1e-15));
  CHECK(world.step_count() == 602);
}
