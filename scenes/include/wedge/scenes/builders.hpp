// Scenes made in code, for tests and benchmarks: the same layouts in any dimension, so that 2D and 3D
// runs can be set beside Box2D and Bullet and the 4D ones scaled from 100 to 10,000 bodies.
#pragma once

#include <cstdint>

#include "wedge/world.hpp"

namespace wedge::scenes {

// A static half-space ground {x : x_1 <= 0} (axis 1 is "up") with the given friction.
template <int N>
BodyId add_ground(World<N>& world, double friction = 0.6);

// A pyramid of equal boxes in the (x_0, x_1) plane: `rows` boxes in the bottom row, one fewer in each row
// above, resting exactly on the ground and on each other (no gaps), centred at the origin on the other
// axes. Box half extents `half` on every axis; density 1000 kg/m^n. Returns the first box's id.
template <int N>
BodyId add_box_pyramid(World<N>& world, int rows, double half = 0.5, double friction = 0.6);

// A tower of `count` equal boxes (half extent `half`) stacked exactly on the ground along x_1.
template <int N>
BodyId add_box_tower(World<N>& world, int count, double half = 0.5, double friction = 0.6);

// `count` boxes (half extent `half`) in layers of a square grid over the horizontal axes (every axis but
// x_1), each turned by a random rotation of up to about 0.3 rad (seeded: the same every run), at a pitch
// of 2 sqrt(N) half extents plus a small gap so that no two overlap, the lowest layer just above the
// ground. They fall and settle into a heap.
template <int N>
BodyId add_box_pile(World<N>& world, int count, std::uint64_t seed = 1, double half = 0.5, double friction = 0.6);

}  // namespace wedge::scenes
