// A pair of bodies the contact stages track from step to step, and the pair list's state (internal; its
// stage is pairs.cpp, contact_system.hpp declares the stages).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "wedge/body.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/detail/broadphase.hpp"
#include "wedge/collision/manifold.hpp"

namespace wedge::contact {

// A pair of bodies whose bounding boxes overlap (or a half-space and a body below its plane), a < b.
// Its fields are in the order the step reads them: the soft step's build reads the pairs in colour
// order, not in memory order, so all it reads comes first (through warm_arm), then what the recycling
// reads; the unpacking at the end of the step, in colour order too, writes warm_normal to
// warm_tangent, side by side.
template <int N>
struct alignas(64) Pair {
  std::uint32_t a = 0, b = 0;
  bool updated = false;    // narrow phase run in this step (false: both asleep, manifold kept)
  bool touching = false;   // received a normal impulse or penetrated in the last step
  bool recycled = false;   // (below)
  bool cached = false;     // (contact recycling, below)
  // Index of its constraint in this step, or -1. (In the first line, with the manifold's head: the
  // events' sweep over every pair reads these alone.)
  int constraint = -1;
  Manifold<N> manifold;
  // Where its points were put in PaperSolver::points or SoftSolver::point_masses by the build numbered `built`
  // (ConstraintGraph::builds), or -1: the last step's when built + 1 is this step's number (last_first).
  // recycled (soft step): this step's manifold is the last step's carried along (recycling.cpp), so a
  // point's normal, lever arms and, for bodies whose inertia is isotropic, effective masses are the
  // same, and the build takes them from the last step's. mass_key: the bodies' 1/m and isotropic 1/I
  // those masses were formed with. (Numbered rather than reset every step: the sweep that starts the
  // build then wrote this line of every pair, and zeroed its impulses on another.)
  int points_first = -1;
  int warm_count = 0;      // (warm start, below)
  std::uint64_t built = 0;
  double approach_speed = 0.0;  // m/s, >= 0: the fastest its points approached when the step began (events)
  std::array<double, 4> mass_key{};
  // Warm start: the contact-stage impulses of the last step per feature id (warm_id below), given back
  // to the points that continue them (same id, or same place), so the iterations start from last
  // step's answer. The impulses the soft step unpacks at the end of the step are together, on a line of
  // their own in 2D (unpack_lane; the keys, warm_id and warm_arm, are kept by the build). (In 3D and up
  // they take three lines or more whatever their alignment, which would cost a line per pair.)
  alignas(N == 2 ? 64 : alignof(double)) std::array<double, kMaxManifoldPoints<N>> warm_normal{};
  std::array<double, kMaxManifoldPoints<N>> normal_impulse{};  // N s, in the last step
  std::array<Vec<N>, kMaxManifoldPoints<N>> warm_tangent = zero_vectors();
  // The lever arms of the manifold's points from a's and b's centres (world frame) in this step: equal
  // to point - centre for a fresh manifold, carried along with each body for a recycled one.
  std::array<Vec<N>, kMaxManifoldPoints<N>> arm_a = zero_vectors(), arm_b = zero_vectors();
  // The warm points' feature ids, and their lever arms from a's centre (world frame), to match points
  // whose id changed by place.
  std::array<std::uint64_t, kMaxManifoldPoints<N>> warm_id{};
  std::array<Vec<N>, kMaxManifoldPoints<N>> warm_arm = zero_vectors();
  // Contact recycling (recycling.cpp): the state when the manifold was last computed (cached), to carry
  // it along while the bodies barely move relative to each other.
  Mat<N> rotation_a = Mat<N>::Identity(), rotation_b = Mat<N>::Identity();  // the bodies' rotations then
  Vec<N> relative_position = Vec<N>::Zero();       // m, b's centre in a's frame then
  std::array<Vec<N>, kMaxManifoldPoints<N>> anchor_a = zero_vectors(), anchor_b = zero_vectors();  // arms then
  std::array<double, kMaxManifoldPoints<N>> base_gap{};  // m, each point's gap then
  bool operator<(const Pair& o) const { return a != o.a ? a < o.a : b < o.b; }

 private:
  // Eigen vectors are not zeroed by {}; GCC rightly warns about copying them uninitialised.
  static std::array<Vec<N>, kMaxManifoldPoints<N>> zero_vectors() {
    std::array<Vec<N>, kMaxManifoldPoints<N>> v;
    v.fill(Vec<N>::Zero());
    return v;
  }
};

// What the next step's warm start matches a pair's points by (warm_matches): their count, feature ids
// and lever arms from a's centre. (Kept as the soft step's build reads the pair, before the solve, since
// nothing the solve does changes them; the impulses follow at the end of the step, unpack_lane.)
template <int N>
inline void keep_warm_keys(Pair<N>& pair, int count) {
  pair.warm_count = count;
  for (int k = 0; k < count; ++k) {
    pair.warm_id[k] = pair.manifold.points[k].id;
    pair.warm_arm[k] = pair.arm_a[k];  // (the points' and lanes' ra)
  }
}

// The pair list (pairs.cpp): the broad phase and its per-body proxies and boxes, the candidate pairs,
// and the persistent sorted list of pairs.
template <int N>
struct PairList {
  BroadPhase<N> broad_phase;
  std::vector<int> proxy;                 // per body: broad-phase proxy, -1 without one
  std::vector<Aabb<N>> box;               // per body: tight world box at the last update
  std::vector<double> radius;             // per body: m, farthest point of its shape from the centre of mass
  std::vector<double> inradius;           // per body: m, nearest point of its surface to the centre of mass
  std::vector<std::uint32_t> halfspaces;  // bodies whose shape is a half-space
  std::vector<typename BroadPhase<N>::Pair> candidate_pairs;
  // The half-space pairs of this step and of the last (when neither they nor the broad phase's
  // changed, candidate_pairs stands).
  std::vector<typename BroadPhase<N>::Pair> halfspace_pairs, previous_halfspace_pairs;
  std::vector<Pair<N>> pairs, next_pairs;  // sorted by (a, b)
  std::vector<std::uint64_t> pair_keys;     // a << 32 | b of each pair, in order (merge_pairs' check)
};

}  // namespace wedge::contact
