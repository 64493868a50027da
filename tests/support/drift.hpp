// Where the bodies of a world are, and how far the farthest has moved since (resting-contact tests).
#pragma once

#include <algorithm>
#include <vector>

#include "wedge/world.hpp"

namespace drift {

template <int N>
std::vector<wedge::Vec<N>> centres(const wedge::World<N>& w) {
  std::vector<wedge::Vec<N>> c;
  for (const wedge::Body<N>& b : w.bodies()) c.push_back(b.center);
  return c;
}

// The largest distance any body's centre moved from `start` (m).
template <int N>
double largest(const wedge::World<N>& w, const std::vector<wedge::Vec<N>>& start) {
  double d = 0.0;
  for (int i = 0; i < w.body_count(); ++i) d = std::max(d, (w.bodies()[i].center - start[i]).norm());
  return d;
}

}  // namespace drift
