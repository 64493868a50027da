// Scenes made in code (builders.hpp); explicitly instantiated for N = 2..6.
#include "wedge/scenes/builders.hpp"

#include <cmath>
#include <memory>
#include <random>

#include "wedge/ga/exp_log.hpp"
#include "wedge/mass.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::scenes {

namespace {

constexpr double kDensity = 1000.0;  // kg/m^n

template <int N>
BodyDef<N> box_def(double half, double friction) {
  BodyDef<N> def = body_def<N>(std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(half))), kDensity);
  def.material.friction = friction;
  def.material.kinetic_friction = friction;
  return def;
}

}  // namespace

template <int N>
BodyId add_ground(World<N>& world, double friction) {
  BodyDef<N> def;
  def.name = "ground";
  def.type = BodyType::Static;
  def.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(Vec<N>::Unit(1), 0.0));
  def.material.friction = friction;
  def.material.kinetic_friction = friction;
  return world.add_body(def);
}

template <int N>
BodyId add_box_pyramid(World<N>& world, int rows, double half, double friction) {
  BodyDef<N> def = box_def<N>(half, friction);
  const double pitch = 2.25 * half;  // a gap of 1/8 of a box between neighbours, as in Box2D's pyramid
  BodyId first{std::uint32_t(world.body_count())};
  for (int row = 0; row < rows; ++row) {
    const int count = rows - row;
    for (int i = 0; i < count; ++i) {
      def.name = "box_" + std::to_string(row) + "_" + std::to_string(i);
      def.position = Vec<N>::Zero();
      def.position[0] = (i - 0.5 * (count - 1)) * pitch;
      def.position[1] = half + 2.0 * half * row;
      world.add_body(def);
    }
  }
  return first;
}

template <int N>
BodyId add_box_tower(World<N>& world, int count, double half, double friction) {
  BodyDef<N> def = box_def<N>(half, friction);
  BodyId first{std::uint32_t(world.body_count())};
  for (int i = 0; i < count; ++i) {
    def.name = "box_" + std::to_string(i);
    def.position = Vec<N>::Zero();
    def.position[1] = half + 2.0 * half * i;
    world.add_body(def);
  }
  return first;
}

template <int N>
BodyId add_box_pile(World<N>& world, int count, std::uint64_t seed, double half, double friction) {
  BodyDef<N> def = box_def<N>(half, friction);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-0.3 / std::sqrt(double(kBiv<N>)), 0.3 / std::sqrt(double(kBiv<N>)));
  // A turned box stays inside the ball of radius half sqrt(N), so this pitch keeps every pair apart.
  const double pitch = 2.0 * half * std::sqrt(double(N)) + 0.1 * half;
  const int side = std::max(1, int(std::ceil(std::pow(double(count), 1.0 / double(N)))));
  int per_layer = 1;
  for (int k = 0; k < N - 1; ++k) per_layer *= side;
  BodyId first{std::uint32_t(world.body_count())};
  for (int n = 0; n < count; ++n) {
    const int layer = n / per_layer;
    int cell = n % per_layer;
    def.name = "box_" + std::to_string(n);
    def.position = Vec<N>::Zero();
    for (int axis = 0; axis < N; ++axis) {
      if (axis == 1) continue;
      def.position[axis] = ((cell % side) - 0.5 * (side - 1)) * pitch;
      cell /= side;
    }
    def.position[1] = 0.5 * pitch + layer * pitch;
    Bivector<N> b;
    for (int k = 0; k < kBiv<N>; ++k) b.c[k] = angle(rng);
    def.rotor = exp<N>(b);
    world.add_body(def);
  }
  return first;
}

#define WEDGE_INSTANTIATE(N)                                                              \
  template BodyId add_ground<N>(World<N>&, double);                                       \
  template BodyId add_box_pyramid<N>(World<N>&, int, double, double);                     \
  template BodyId add_box_tower<N>(World<N>&, int, double, double);                       \
  template BodyId add_box_pile<N>(World<N>&, int, std::uint64_t, double, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::scenes
