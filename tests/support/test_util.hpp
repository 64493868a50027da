// Small helpers shared by the test files: dimension tags for TEMPLATE_TEST_CASE and random GA values.
#pragma once

#include <random>
#include <type_traits>

#include "wedge/ga/types.hpp"

using D2 = std::integral_constant<int, 2>;
using D3 = std::integral_constant<int, 3>;
using D4 = std::integral_constant<int, 4>;
using D5 = std::integral_constant<int, 5>;
using D6 = std::integral_constant<int, 6>;

// A bivector with independent normal components of standard deviation `scale`.
template <int N>
wedge::Bivector<N> random_bivector(std::mt19937_64& rng, double scale) {
  std::normal_distribution<double> nd;
  wedge::Bivector<N> b;
  for (int i = 0; i < wedge::kBiv<N>; ++i) b[i] = scale * nd(rng);
  return b;
}
