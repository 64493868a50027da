// Where the bodies of a world are, and how far the farthest has moved since (resting-contact tests).
#pragma once

#include <algorithm>
#include <cmath>
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

// The soft step's contacts are springs: a point with normal effective mass m_p pushes back with
// m_p (2 pi f)^2 per metre of penetration (f = contact_hertz, capped at an eighth of the sub-step rate).
// A tower of `count` cubes (mass m, half extent a, isotropic inertia 2 m a^2 / 3) standing face on face
// on the ground: joint j (0: the ground) carries (count - j) m g over its 2^(N-1) corners, each with
//   1 / m_p = (1 + 3 (N - 1) / 2) (1/m, or 2/m between two cubes)
// (K = 1/m + |r ^ n|^2 / I per body, |r ^ n|^2 = (N - 1) a^2 at a corner). The top sinks by the sum of
// the joints' penetrations (m), independent of m and a. A pyramid sinks less: each box rests on two.
template <int N>
double tower_sag(int count, const wedge::ContactSettings& c, double h, double g = 9.81) {
  const double f = std::min(c.contact_hertz, 0.125 * c.substeps / h);
  const double omega2 = std::pow(2.0 * M_PI * f, 2), per_mass = 1.0 + 1.5 * (N - 1), points = 1 << (N - 1);
  double sag = 0.0;
  for (int j = 0; j < count; ++j) sag += (count - j) * g / points * per_mass * (j == 0 ? 1.0 : 2.0) / omega2;
  return sag;
}

}  // namespace drift
