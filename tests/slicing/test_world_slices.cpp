// slicing::WorldSlices (the World-to-slice glue shared by render, slice, the viewer and OpenXR), 4D and
// 5D: which bodies the slice meets follows from their w alone (a tesseract of half size a meets the slice
// w = w0 iff |w - w0| <= a), the slice of a tesseract cut straight is its 3D cube (volume (2a)^3), the
// ground is the half-space's cut, and moving the slice moves what is seen.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "wedge/mass.hpp"
#include "wedge/slicing/world_slices.hpp"

using namespace wedge;

namespace {
template <int N>
World<N> row_in_w() {
  World<N> world;
  BodyDef<N> ground;
  ground.type = BodyType::Static;
  Vec<N> up = Vec<N>::Zero();
  up[1] = 1.0;
  ground.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(up, 0.0));
  world.add_body(ground);
  for (int i = 0; i < 3; ++i) {  // at w = 0, 0.4, 2 (half size 0.5)
    BodyDef<N> d;
    d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(0.5)));
    const MassProperties<N> mp = box_mass_properties<N>(Vec<N>::Constant(0.5), 1.0);
    d.mass = mp.mass;
    d.inertia = mp.inertia;
    d.position = 0.5 * up;
    d.position[0] = 2.0 * i;
    d.position[N - 1] = i == 0 ? 0.0 : (i == 1 ? 0.4 : 2.0);
    world.add_body(d);
  }
  return world;
}

double volume(const slicing::DisplayMesh<3>& m) {  // closed outward triangle mesh: divergence theorem
  double v = 0.0;
  for (const auto& c : m.cells) v += m.vertices[c[0]].dot(m.vertices[c[1]].cross(m.vertices[c[2]])) / 6.0;
  return v;
}
}  // namespace

TEST_CASE("WorldSlices: what the slice meets follows from w", "[slicing]") {
  const World<4> world = row_in_w<4>();
  for (double w0 : {0.0, 0.3, 1.8}) {
    slicing::WorldSlices<4> slices(world, {w0}, 1);
    REQUIRE(slices.entries().size() == 3);  // the half-space is not sliced
    std::vector<slicing::DisplayMesh<3>> meshes;
    slices.slice(world, meshes);
    const double w[3] = {0.0, 0.4, 2.0};
    for (int k = 0; k < 3; ++k) {
      INFO("w0 " << w0 << ", body " << k);
      const bool meets = std::abs(w[k] - w0) <= 0.5;
      CHECK(meshes[k].empty() == !meets);
      CHECK(slices.slice_bound(world, std::size_t(k)).has_value() == (std::abs(w[k] - w0) < 0.5 * std::sqrt(4.0)));
      if (meets) CHECK(volume(meshes[k]) == Approx(1.0).epsilon(1e-9));  // the unit cube
    }
    const auto g = slices.ground(world);
    REQUIRE(g);
    CHECK((g->first - Eigen::Vector3d::UnitY()).norm() < 1e-12);
    CHECK(g->second == Approx(0.0).margin(1e-12));
  }
}

TEST_CASE("WorldSlices: 5D offsets go to x4, then x3", "[slicing]") {
  const World<5> world = row_in_w<5>();  // the row is offset along x4
  std::vector<slicing::DisplayMesh<3>> meshes;
  slicing::WorldSlices<5> at_two(world, {2.0, 0.0}, 1);
  at_two.slice(world, meshes);
  CHECK(meshes[0].empty());
  CHECK_FALSE(meshes[2].empty());
  slicing::WorldSlices<5> off(world, {2.0, 0.7}, 1);  // x3 = 0.7: beyond every body's half size
  off.slice(world, meshes);
  for (const auto& m : meshes) CHECK(m.empty());
}

TEST_CASE("WorldSlices: bodies culled by their bounding ball are exactly those the slicer leaves empty",
          "[slicing]") {
  // The cull skips a body whose bounding ball misses the flat. Sliced without it (a BodySlicer of the same
  // mesh), every body gives the same triangles, for slices sweeping across the bodies' faces in w,
  // and at w = +-0.5, -0.1, 0.9, 1.5 and 2.5, where the slice touches a face (vertices on the flat).
  const World<4> world = row_in_w<4>();
  std::vector<double> ws = {-0.5, 0.5, -0.1, 0.9, 1.5, 2.5};
  for (int i = -8; i <= 28; ++i) ws.push_back(0.1 * i + 0.013);
  for (double w0 : ws) {
    slicing::WorldSlices<4> slices(world, {w0}, 1);
    std::vector<slicing::DisplayMesh<3>> meshes;
    slices.slice(world, meshes);
    for (std::size_t k = 0; k < slices.entries().size(); ++k) {
      const BodyId id{std::uint32_t(slices.entries()[k].body)};
      slicing::BodySlicer<4> plain(slicing::display_mesh<4>(*world.shape(id), 1));
      const Body<4>& b = world.body(id);
      const slicing::DisplayMesh<3> expected = plain.slice({to_matrix(b.rotor), b.position()}, slices.chain());
      INFO("w0 " << w0 << ", body " << k);
      CHECK(meshes[k].cells.size() == expected.cells.size());
      CHECK(meshes[k].vertices == expected.vertices);
    }
  }
}

TEST_CASE("WorldSlices: the coarse level slices round shapes at its own tessellation, polytopes as they are",
          "[slicing]") {
  World<4> world = row_in_w<4>();
  BodyDef<4> ball;
  ball.shape = std::make_shared<const Shape<4>>(Shape<4>::ball(0.5));
  ball.position = Vec<4>(0.0, 2.0, 0.0, 0.1);
  world.add_body(ball);
  slicing::WorldSlices<4> slices(world, {0.0}, 8, 5);
  std::vector<slicing::DisplayMesh<3>> fine, coarse;
  slices.slice(world, fine, slicing::Detail::Fine);
  slices.slice(world, coarse, slicing::Detail::Coarse);
  REQUIRE(slices.entries().size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    const BodyId id{std::uint32_t(slices.entries()[k].body)};
    const Body<4>& b = world.body(id);
    const slicing::Placement<4> pl{to_matrix(b.rotor), b.position()};
    INFO("body " << k);
    CHECK(fine[k].vertices == slicing::slice_to_3d(slicing::display_mesh<4>(*world.shape(id), 8), pl, slices.chain()).vertices);
    CHECK(coarse[k].vertices == slicing::slice_to_3d(slicing::display_mesh<4>(*world.shape(id), 5), pl, slices.chain()).vertices);
    CHECK(slices.entries()[k].coarse.has_value() == (k == 3));  // the boxes need no second mesh
  }
  CHECK(coarse[3].cells.size() < fine[3].cells.size() / 2);  // (5/8)^2 of the triangles, about
  CHECK(!coarse[3].empty());
}
