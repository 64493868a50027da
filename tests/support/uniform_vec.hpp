// Random vectors with independent uniform components, for the collision tests (boxes, positions,
// displacements).
#pragma once

#include <random>

#include "wedge/ga/types.hpp"

// A vector with independent components uniform in [lo, hi).
template <int N>
wedge::Vec<N> uniform_vec(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  wedge::Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = u(rng);
  return v;
}
