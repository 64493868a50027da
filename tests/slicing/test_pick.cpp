// slicing::pick against closed forms: the slice of a tesseract at w = 0 is a cube, so a ray meets it where
// the slab intervals first overlap (exact up to round-off: its faces are flat); a 4-ball's slice is a
// tessellated sphere, inscribed: met no nearer than the true sphere, at a point within the sagitta of it
// (3% of the radius at 8 subdivisions). The hit point maps back into the world on the slice.
#include <catch2/catch.hpp>
#include <random>

#include "wedge/slicing/pick.hpp"
#include "wedge/slicing/world_slices.hpp"
#include "wedge/mass.hpp"

using namespace wedge;

namespace {
World<4> two_bodies() {
  World<4> world;
  for (int i = 0; i < 2; ++i) {
    BodyDef<4> d;
    d.shape = std::make_shared<const Shape<4>>(i == 0 ? Shape<4>::box(Vec<4>(0.5, 0.4, 0.3, 0.5)) : Shape<4>::ball(0.5));
    d.position = Vec<4>(i == 0 ? -1.0 : 1.0, 0, 0, i == 0 ? 0.0 : 0.2);
    world.add_body(d);
  }
  return world;
}
}  // namespace

TEST_CASE("pick: rays against the slice of a tesseract and of a 4-ball", "[slicing][pick]") {
  const World<4> world = two_bodies();
  slicing::WorldSlices<4> slices(world, {0.0}, 8);
  std::vector<slicing::DisplayMesh<3>> meshes;
  slices.slice(world, meshes);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int box_hits = 0, ball_hits = 0;
  const double r = std::sqrt(0.5 * 0.5 - 0.2 * 0.2);  // the ball's slice at w = 0, 0.2 from its centre
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d origin{4.0 * u(rng), 2.0 + u(rng), 5.0};  // (braces: drawn left to right)
    const Eigen::Vector3d target = trial % 2 ? Eigen::Vector3d{-1.0 + 0.5 * u(rng), 0.4 * u(rng), 0.3 * u(rng)}
                                             : Eigen::Vector3d{1.0 + 0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng)};
    const Eigen::Vector3d d = (target - origin).normalized();
    const auto hit = slicing::pick(meshes, origin, d);
    // Truth: the cube (slab method) and the sphere (closed form).
    double cube = INFINITY, lo = 0, hi = INFINITY;
    const Eigen::Vector3d c0(-1, 0, 0), half(0.5, 0.4, 0.3);
    for (int k = 0; k < 3; ++k) {
      double t1 = (c0[k] - half[k] - origin[k]) / d[k], t2 = (c0[k] + half[k] - origin[k]) / d[k];
      if (t1 > t2) std::swap(t1, t2);
      lo = std::max(lo, t1), hi = std::min(hi, t2);
    }
    if (lo <= hi) cube = lo;
    const Eigen::Vector3d rel = origin - Eigen::Vector3d(1, 0, 0);
    const double b = -rel.dot(d), disc = b * b - (rel.squaredNorm() - r * r);
    const double sphere = disc >= 0 ? b - std::sqrt(disc) : INFINITY;
    if (cube < sphere) {
      REQUIRE(hit);
      CHECK(hit->mesh == 0);
      CHECK(hit->distance == Approx(cube).margin(1e-9));
      ++box_hits;
    } else if (std::isfinite(sphere) && disc > 0.05 * r * r) {  // (not grazing: the tessellation decides)
      REQUIRE(hit);
      CHECK(hit->mesh == 1);
      // The tessellation is inscribed: the hit is never nearer than the true sphere, and lies on a
      // triangle whose points are within the sagitta of it (radially, 3% of r at 8 subdivisions).
      CHECK(hit->distance >= sphere - 1e-9);
      const double radial = (hit->point - Eigen::Vector3d(1, 0, 0)).norm();
      CHECK(radial <= r + 1e-9);
      CHECK(radial >= 0.97 * r);
      ++ball_hits;
    }
    if (hit) {
      CHECK(hit->normal.dot(d) <= 0.0);
      const Vec<4> x = slicing::slice_to_world(slices.flat(), hit->point);
      CHECK(x[3] == 0.0);  // on the slice w = 0
      CHECK((x.head<3>() - hit->point).norm() < 1e-12);
    }
  }
  CHECK(box_hits > 50);
  CHECK(ball_hits > 50);
  CHECK_FALSE(slicing::pick(meshes, Eigen::Vector3d(0, 5, 5), Eigen::Vector3d(0, 1, 0)));  // away from all
  CHECK_FALSE(slicing::pick(meshes, Eigen::Vector3d(-1, 0, 5), Eigen::Vector3d(0, 0, -1), 4.0));  // too short
}
