// The narrow phase through its dispatch table: contact manifolds against configurations whose contact
// points, depths and normals are known exactly (resting faces, edges, analytic ball geometry), symmetry
// of the table, and no NaN on degenerate configurations. The random-pair checks against independent
// oracles (LP, Minkowski hulls, Bullet) are in test_collision_oracles.cpp.
#include <catch2/catch.hpp>
#include <cmath>

#include "test_util.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/hull.hpp"

using namespace wedge;

namespace {

template <int N>
Transform<N> place(const Vec<N>& p, const Rotor<N>& r = Rotor<N>::identity()) {
  return {p, to_matrix(r)};
}

// The 3-volume of the convex hull of the points' (x, z, w) coordinates: how much of a 4D contact cell
// whose normal is y they span.
double span_volume_xzw(const Manifold<4>& m) {
  std::vector<Vec<3>> p;
  for (int i = 0; i < m.count; ++i) p.push_back(Vec<3>(m.points[i].point[0], m.points[i].point[2], m.points[i].point[3]));
  if (p.size() < 4) return 0.0;
  try {
    return signed_volume<3>(convex_hull<3>(p).mesh);
  } catch (const Error&) {
    return 0.0;  // flat: spans no volume
  }
}

// A rotation in the planes e02, e03, e23 only: it keeps the y axis, so a box stays flat on y = const.
Rotor<4> random_xzw_rotor(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  Bivector<4> b;
  b[1] = u(rng);  // e02
  b[2] = u(rng);  // e03
  b[5] = u(rng);  // e23
  return exp(b);
}

template <int N>
void check_finite(const Manifold<N>& m) {
  REQUIRE(std::isfinite(m.depth));
  REQUIRE(m.normal.allFinite());
  CHECK(m.normal.norm() == Approx(1.0).epsilon(1e-12));
  for (int i = 0; i < m.count; ++i) {
    REQUIRE(m.points[i].point.allFinite());
    REQUIRE(std::isfinite(m.points[i].depth));
  }
}

}  // namespace

TEST_CASE("A tesseract resting on the ground gives its 8 bottom corners, rotated flat or not", "[narrow]") {
  const Shape<4> ground = Shape<4>::halfspace(Vec<4>::UnitY(), 0.0);
  const Shape<4> cube = Shape<4>::box(Vec<4>::Constant(0.5));
  const double sink = 1e-3;  // 1 mm into the ground
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Rotor<4> r = trial == 0 ? Rotor<4>::identity() : random_xzw_rotor(rng);
    const Vec<4> pos(0.3, 0.5 - sink, -0.2, 0.7);
    const Manifold<4> m = collide(ground, place<4>(Vec<4>::Zero()), cube, place(pos, r));
    check_finite(m);
    REQUIRE(m.intersecting);
    CHECK(m.depth == Approx(sink).margin(1e-12));
    CHECK((m.normal - Vec<4>::UnitY()).norm() < 1e-12);
    REQUIRE(m.count == 8);
    // The points are the bottom cell's corners (halfway into the 1 mm overlap) and span its 3-volume 1 m^3.
    for (int i = 0; i < m.count; ++i) {
      CHECK(m.points[i].depth == Approx(sink).margin(1e-12));
      CHECK(m.points[i].point[1] == Approx(-0.5 * sink).margin(1e-12));
    }
    CHECK(span_volume_xzw(m) == Approx(1.0).epsilon(1e-9));
    // Either order of the pair gives the same contact, normal reversed.
    const Manifold<4> back = collide(cube, place(pos, r), ground, place<4>(Vec<4>::Zero()));
    CHECK((back.normal + m.normal).norm() < 1e-12);
    CHECK(back.count == 8);
  }
}

TEST_CASE("A tesseract resting on a larger tesseract: face-to-face manifold spans the contact cell", "[narrow]") {
  const Shape<4> base = Shape<4>::box(Vec<4>::Constant(1.0));
  const Shape<4> top = Shape<4>::box(Vec<4>::Constant(0.5));
  const double sink = 2e-3;
  std::mt19937_64 rng(12);
  for (int trial = 0; trial < 50; ++trial) {
    const Rotor<4> r = trial == 0 ? Rotor<4>::identity() : random_xzw_rotor(rng);
    // Fully on the base's top cell: the rotated 1 m cube fits inside the 2 m one (circumradius 0.87 < 1).
    const Vec<4> pos(0.0, 1.5 - sink, 0.0, 0.0);
    const Manifold<4> m = collide(base, place<4>(Vec<4>::Zero()), top, place(pos, r));
    check_finite(m);
    REQUIRE(m.intersecting);
    CHECK(m.depth == Approx(sink).margin(1e-9));
    CHECK((m.normal - Vec<4>::UnitY()).norm() < 1e-9);
    REQUIRE(m.count == 8);
    for (int i = 0; i < m.count; ++i) CHECK(m.points[i].depth == Approx(sink).margin(1e-9));
    CHECK(span_volume_xzw(m) == Approx(1.0).epsilon(1e-9));
  }
}

TEST_CASE("A tesseract hanging over the edge of another: the points span exactly the overlap", "[narrow]") {
  const Shape<4> base = Shape<4>::box(Vec<4>::Constant(1.0));
  const Shape<4> top = Shape<4>::box(Vec<4>::Constant(0.5));
  // Shifted by 0.8 in x and 0.9 in w: the overlap cell is x in [0.3, 1], z in [-0.5, 0.5], w in [0.4, 1].
  const Manifold<4> m =
      collide(base, place<4>(Vec<4>::Zero()), top, place<4>(Vec<4>(0.8, 1.499, 0.0, 0.9)));
  REQUIRE(m.intersecting);
  CHECK(m.depth == Approx(1e-3).margin(1e-9));
  REQUIRE(m.count == 8);
  CHECK(span_volume_xzw(m) == Approx(0.7 * 1.0 * 0.6).epsilon(1e-9));
  for (int i = 0; i < m.count; ++i) {
    CHECK(m.points[i].point[0] >= 0.3 - 1e-12);
    CHECK(m.points[i].point[3] >= 0.4 - 1e-12);
  }
}

TEST_CASE("Edge-face contact in 4D: a tesseract standing on an edge touches at the edge's two ends", "[narrow]") {
  // Rotate the body so that its direction (1, 1, 1, 0)/sqrt3 points down (-y): its lowest feature is then
  // the edge along the body's w axis at x = y = z = +h, i.e. the corners (h, h, h, +-h).
  const double h = 0.5;
  const Vec<4> body_down = Vec<4>(1, 1, 1, 0).normalized();
  // The rotation in the plane of body_down and -y that takes one to the other (a single plane rotation).
  const Vec<4> target = -Vec<4>::UnitY();
  const Vec<4> u = body_down, v = (target - target.dot(u) * u).normalized();
  const double angle = std::acos(std::clamp(u.dot(target), -1.0, 1.0));
  Mat<4> rot = Mat<4>::Identity() + std::sin(angle) * (v * u.transpose() - u * v.transpose()) +
               (std::cos(angle) - 1.0) * (u * u.transpose() + v * v.transpose());
  REQUIRE((rot * body_down - target).norm() < 1e-12);
  const double sink = 1e-3;
  const double lowest = h * std::sqrt(3.0);  // distance of the edge below the centre
  const Transform<4> tb{Vec<4>(0.1, lowest - sink, 0.2, 0.3), rot};
  const Vec<4> e1 = tb.apply(Vec<4>(h, h, h, -h)), e2 = tb.apply(Vec<4>(h, h, h, h));

  const Shape<4> cube = Shape<4>::box(Vec<4>::Constant(h));
  for (const Shape<4>& floor : {Shape<4>::halfspace(Vec<4>::UnitY(), 0.0), Shape<4>::box(Vec<4>(3, 1, 3, 3))}) {
    const Transform<4> ta = place<4>(floor.bounded() ? Vec<4>(0, -1, 0, 0) : Vec<4>::Zero());
    const Manifold<4> m = collide(floor, ta, cube, tb);
    check_finite(m);
    REQUIRE(m.intersecting);
    CHECK(m.depth == Approx(sink).margin(1e-9));
    CHECK((m.normal - Vec<4>::UnitY()).norm() < 1e-9);
    REQUIRE(m.count == 2);
    // The two points are the edge's ends, moved up by half the depth.
    const Vec<4> half = 0.5 * sink * Vec<4>::UnitY();
    const double d1 = std::min((m.points[0].point - (e1 + half)).norm(), (m.points[1].point - (e1 + half)).norm());
    const double d2 = std::min((m.points[0].point - (e2 + half)).norm(), (m.points[1].point - (e2 + half)).norm());
    CHECK(d1 < 1e-9);
    CHECK(d2 < 1e-9);
  }
}

TEMPLATE_TEST_CASE("Ball against ball: depth r_a + r_b - d along the centre line", "[narrow]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  std::mt19937_64 rng(13);
  std::normal_distribution<double> nd;
  const Shape<N> a = Shape<N>::ball(0.7), b = Shape<N>::ball(0.4);
  for (int t = 0; t < 100; ++t) {
    const Vec<N> pa = Vec<N>::NullaryExpr([&] { return nd(rng); });
    const Vec<N> pb = pa + Vec<N>::NullaryExpr([&] { return 0.8 * nd(rng); });
    const Manifold<N> m = collide(a, place<N>(pa), b, place<N>(pb));
    const double d = (pb - pa).norm();
    CHECK(m.depth == Approx(1.1 - d).margin(1e-12));
    CHECK(m.intersecting == (d <= 1.1));
    CHECK((m.normal - (pb - pa) / d).norm() < 1e-12);
    if (m.intersecting) {
      REQUIRE(m.count == 1);
      // The point lies halfway between the two surfaces on the centre line.
      CHECK((m.points[0].point - (pa + (0.7 - 0.5 * (1.1 - d)) * m.normal)).norm() < 1e-12);
    }
  }
}

TEMPLATE_TEST_CASE("Ball against half-space and against a box face, edge and corner", "[narrow]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const double r = 0.3;
  const Shape<N> ball = Shape<N>::ball(r);
  const Shape<N> box = Shape<N>::box(Vec<N>::Constant(1.0));
  // Centre beyond j coordinates of the unit box by 0.1 each: the nearest feature is an (N-j)-face, at
  // distance 0.1 sqrt(j), and the normal points from the ball to that face's nearest point.
  for (int j = 1; j <= N; ++j) {
    Vec<N> c = Vec<N>::Zero();
    for (int i = 0; i < j; ++i) c[i] = 1.1;
    const Manifold<N> m = collide(ball, place<N>(c), box, place<N>(Vec<N>::Zero()));
    const double dist = 0.1 * std::sqrt(double(j));
    CHECK(m.depth == Approx(r - dist).margin(1e-12));
    Vec<N> expected = Vec<N>::Zero();
    for (int i = 0; i < j; ++i) expected[i] = -1.0 / std::sqrt(double(j));
    CHECK((m.normal - expected).norm() < 1e-12);
  }
  // Inside the box: the ball must leave through the nearest face.
  Vec<N> c = Vec<N>::Zero();
  c[N - 1] = 0.9;
  const Manifold<N> in = collide(ball, place<N>(c), box, place<N>(Vec<N>::Zero()));
  CHECK(in.depth == Approx(r + 0.1).margin(1e-12));
  CHECK((in.normal + Vec<N>::Unit(N - 1)).norm() < 1e-12);  // b (the box) is pushed down, away from the ball
  const Manifold<N> g = collide(Shape<N>::halfspace(Vec<N>::Unit(0), 0.0), place<N>(Vec<N>::Zero()), ball,
                                place<N>(Vec<N>(Vec<N>::Unit(0) * 0.25)));
  CHECK(g.depth == Approx(0.05).margin(1e-12));
  REQUIRE(g.count == 1);
}

TEST_CASE("A cylinder standing on the ground touches around its end disk", "[narrow]") {
  // Cylinder: disk on axes {0, 1}, interval along axis 2. Stand it with the axis along y.
  const Shape<3> cyl = Shape<3>::cylinder(0.4, 0.6);
  Mat<3> rot;
  rot << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // body z -> world y
  const Transform<3> t{Vec<3>(0.0, 0.6 - 1e-3, 0.0), rot};
  const Manifold<3> m = collide(Shape<3>::halfspace(Vec<3>::UnitY(), 0.0), place<3>(Vec<3>::Zero()), cyl, t);
  REQUIRE(m.intersecting);
  CHECK(m.depth == Approx(1e-3).margin(1e-12));
  REQUIRE(m.count == 4);  // eight rim points reduced to the capacity of a 3D manifold
  double spread = 0.0;
  for (int i = 0; i < m.count; ++i) {
    CHECK(Vec<2>(m.points[i].point[0], m.points[i].point[2]).norm() == Approx(0.4).epsilon(1e-12));
    for (int j = 0; j < i; ++j) spread = std::max(spread, (m.points[i].point - m.points[j].point).norm());
  }
  CHECK(spread == Approx(0.8).epsilon(1e-12));  // a diameter is kept: the points span the disk
}

TEMPLATE_TEST_CASE("Every pair of shape kinds collides in both orders with opposite normals", "[narrow]", D3, D4, D5) {
  constexpr int N = TestType::value;
  std::vector<Vec<N>> simplex;
  for (int i = 0; i < N; ++i) simplex.push_back(Vec<N>::Unit(i) * 0.8);
  simplex.push_back(Vec<N>::Constant(-0.3));
  std::vector<Shape<N>> shapes = {Shape<N>::box(Vec<N>::Constant(0.5)), Shape<N>::ball(0.5),
                                  Shape<N>::polytope(simplex), Shape<N>::cylinder(0.5, 0.4),
                                  Shape<N>::halfspace(Vec<N>::Unit(1), 0.0)};
  std::mt19937_64 rng(14);
  for (std::size_t i = 0; i < shapes.size(); ++i)
    for (std::size_t j = 0; j < shapes.size(); ++j) {
      if (!shapes[i].bounded() && !shapes[j].bounded()) continue;
      for (int t = 0; t < 20; ++t) {
        const Transform<N> ta = place<N>(Vec<N>::Zero(), exp(random_bivector<N>(rng, 1.0)));
        const Transform<N> tb = place<N>(Vec<N>(Vec<N>::Unit(1) * (0.2 + 0.05 * t)), exp(random_bivector<N>(rng, 1.0)));
        const Manifold<N> ab = collide(shapes[i], ta, shapes[j], tb);
        const Manifold<N> ba = collide(shapes[j], tb, shapes[i], ta);
        check_finite(ab);
        check_finite(ba);
        CHECK(ab.intersecting == ba.intersecting);
        CHECK(ab.depth == Approx(ba.depth).margin(1e-6));
        if (std::abs(ab.depth) > 1e-6) CHECK((ab.normal + ba.normal).norm() < 1e-4);
      }
    }
}

TEMPLATE_TEST_CASE("Degenerate configurations give finite answers", "[narrow]", D2, D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  const Shape<N> box = Shape<N>::box(Vec<N>::Constant(0.5));
  const Shape<N> ball = Shape<N>::ball(0.5);
  const Transform<N> at0 = place<N>(Vec<N>::Zero());
  // Coincident shapes, a ball centred on a box's corner, boxes touching exactly.
  check_finite(collide(box, at0, box, at0));
  check_finite(collide(ball, at0, ball, at0));
  check_finite(collide(ball, at0, box, at0));
  check_finite(collide(ball, place<N>(Vec<N>::Constant(0.5)), box, at0));
  const Manifold<N> touch = collide(box, at0, box, place<N>(Vec<N>(Vec<N>::Unit(0))));
  check_finite(touch);
  CHECK(touch.depth == Approx(0.0).margin(1e-12));
}

TEST_CASE("Feature ids persist while the same features touch, and tell the points apart", "[narrow]") {
  const Shape<4> base = Shape<4>::box(Vec<4>::Constant(1.0));
  const Shape<4> top = Shape<4>::box(Vec<4>::Constant(0.5));
  const Shape<4> ground = Shape<4>::halfspace(Vec<4>::UnitY(), 0.0);
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  for (const bool on_ground : {true, false}) {
    auto contact = [&](const Vec<4>& shift, const Rotor<4>& r) {
      const Vec<4> p = Vec<4>(0.1, on_ground ? 0.499 : 1.499, -0.1, 0.2) + shift;
      return on_ground ? collide(ground, place<4>(Vec<4>::Zero()), top, place(p, r))
                       : collide(base, place<4>(Vec<4>::Zero()), top, place(p, r));
    };
    const Manifold<4> first = contact(Vec<4>::Zero(), Rotor<4>::identity());
    REQUIRE(first.count == 8);
    std::vector<std::uint64_t> ids;
    for (int i = 0; i < first.count; ++i) ids.push_back(first.points[i].id);
    std::sort(ids.begin(), ids.end());
    CHECK(std::adjacent_find(ids.begin(), ids.end()) == ids.end());  // 8 distinct ids
    // Small motions within the ground plane (1 mm, a few mrad): the same corners touch, the same ids.
    for (int t = 0; t < 20; ++t) {
      Bivector<4> b;
      b[1] = 3 * jitter(rng), b[2] = 3 * jitter(rng), b[5] = 3 * jitter(rng);
      const Manifold<4> m = contact(Vec<4>{jitter(rng), 0.0, jitter(rng), jitter(rng)}, exp(b));
      REQUIRE(m.count == 8);
      std::vector<std::uint64_t> now;
      for (int i = 0; i < m.count; ++i) now.push_back(m.points[i].id);
      std::sort(now.begin(), now.end());
      CHECK(now == ids);
    }
  }
}

// Box pairs meeting at a mixed (edge-like) SAT axis: one box over the other, both turned at random
// and turned almost alike (relative turn 1e-2 .. 1e-8 rad), or both tilted a little. Nearly parallel
// supporting features make the least-squares point of closest approach nearly singular; every contact
// point must still lie on both boxes, within the depth and the margin. A 4D pile once got a point 6 m
// from both, whose lever arm made K ~ 1e16 and the solver produce NaN. Checked for contacts shallower
// than 5 cm, as in simulation; in deep overlaps the single point of a mixed axis is an approximation.
TEMPLATE_TEST_CASE("Contact points of nearly parallel box edges lie on both boxes", "[narrow]", D3, D4, D5) {
  constexpr int N = TestType::value;
  const Vec<N> half = Vec<N>::Constant(0.5);
  const Shape<N> box = Shape<N>::box(half);
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto random_bivector = [&](double scale) {
    Bivector<N> b;
    for (int i = 0; i < kBiv<N>; ++i) b[i] = scale * gauss(rng);
    return b;
  };
  // How far outside the box placed by t the point lies (<= 0: inside).
  auto outside = [&](const Vec<N>& p, const Transform<N>& t) {
    return (Vec<N>(t.rotation.transpose() * (p - t.position)).cwiseAbs() - half).maxCoeff();
  };
  int single = 0, checked = 0;
  for (const bool alike : {true, false}) {
    for (int trial = 0; trial < 3000; ++trial) {
      const Mat<N> ra = to_matrix(exp(random_bivector(alike ? 1.0 : 0.05)));
      const Mat<N> rb = alike ? Mat<N>(ra * to_matrix(exp(random_bivector(std::pow(10.0, -2.0 - 6.0 * unit(rng))))))
                              : to_matrix(exp(random_bivector(std::pow(10.0, -1.0 - 3.0 * unit(rng)))));
      Vec<N> pos;
      for (int i = 0; i < N; ++i) pos[i] = 0.3 * gauss(rng);
      pos[1] = 1.0 - 0.01 * unit(rng);
      const Transform<N> ta{Vec<N>::Zero(), ra}, tb{pos, rb};
      const Manifold<N> m = collide(box, ta, box, tb);
      check_finite(m);
      if (m.count == 1) ++single;
      for (int k = 0; k < m.count; ++k) {
        const ContactPoint<N>& p = m.points[k];
        if (std::abs(p.depth) > 0.05) continue;
        ++checked;
        const double allowed = std::abs(p.depth) + 0.02 + 1e-9;  // depth plus the default margin
        INFO("trial " << trial << " point " << p.point.transpose() << " depth " << p.depth);
        CHECK(outside(p.point, ta) <= allowed);
        CHECK(outside(p.point, tb) <= allowed);
      }
    }
  }
  CHECK(single > 1000);  // many trials did meet at a mixed axis (one point)
  CHECK(checked > 1000);
}
