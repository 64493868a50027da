// The contact machinery World::step runs (internal). One object per world holds the broad phase, the
// persistent pair list, the step's constraints, the solver's body copies and the islands. Each stage is
// a free function, defined in its own file:
//   find_contacts      find_contacts.cpp  the stages below, in order; wakes touched islands
//     update_pairs       pairs.cpp          broad phase, the sorted pair list (add_body: a body's proxy)
//     collide_pairs      collide.cpp        narrow phase, manifolds recycled (recycling.cpp) or collided
//     load_solver_bodies build.cpp          the solver's copies of the bodies
//     build_constraints  build.cpp          the constraints' points (update_constraint_graph in
//                                           constraint_graph.cpp places them: seeds, colours, lanes)
//   process_collisions  solver.cpp      restitution on predicted positions (before the velocity update)
//   process_contacts    solver.cpp      restitution 0, shock propagation, split-impulse position correction
//   integrate_positions solver.cpp      the paper's position update, with its pseudo velocities
//   prepare_soft_step,  soft_step.cpp   the soft step's stages instead of the three above (below)
//     solve_substep ...
//   solve_continuous    continuous.cpp  a fast body put back where it would first reach a static shape
//   update_islands      islands.cpp     islands of touching bodies, sleeping, the contact graph's levels
//   report_events       events.cpp      began/stopped touching, sorted by pair
// Grabs (grab.cpp) are solved inside process_contacts, before the contacts in every pass.
// Everything runs in creation order of the bodies and sorted order of the pairs (the soft step's
// constraints in colour order, itself a function of the pair order), so a step is a function of the
// state alone (bit-identical on every run).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "linalg/fixed_size.hpp"  // set_effective_masses: the tangent mass

#include "wedge/body.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/detail/broadphase.hpp"
#include "wedge/contact.hpp"
#include "wedge/grab.hpp"
#include "wedge/profile.hpp"
#include "contact/wide.hpp"
#include "parallel/workers.hpp"

namespace wedge::dynamics {
template <int N>
struct Motion;  // dynamics/integrate.hpp
}  // namespace wedge::dynamics

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

// A body's velocities as the solvers see them, and for the soft step what its sub-steps integrate and
// how far it has moved: all that the soft step's sweeps over the bodies touch, and nothing else (its
// masses are in BodyMass, the paper's solver's pseudo velocities and levels in PaperBody). What the
// sweeps read most comes first: the passes gather v and w, the sweeps between them these and the warm
// start, the snapshot and the velocity integration.
template <int N>
struct alignas(64) SolverBody {
  Vec<N> v = Vec<N>::Zero();
  Bivector<N> w{};
  bool frozen = false;  // infinite mass for the current shock-propagation level (soft step: does not move)
  bool integrates = false;  // moves, with neither a torque nor a gyroscopic term (else it is apart)
  bool advances = false;    // not static and awake: the soft step's position update moves it
  bool apart = false;       // soft step: moves, and integrate_velocities_apart integrates its velocities
  // Soft step: the velocity change that the contacts' accumulated impulses make, the warm start of the
  // next sub-step (soft_step.cpp, warm_start_substep).
  Vec<N> warm_v = Vec<N>::Zero();
  Bivector<N> warm_w{};
  Vec<N> v0 = Vec<N>::Zero();  // velocities before the stage (its energy check) or soft-step pass
  Bivector<N> w0{};
  // Soft step: a sub-step's velocity integration, the same for each of the step's sub-steps
  // (prepare_soft_step, integrate_substep_velocity): v = (v + dv) decay_v, w = w decay_w, where integrates.
  Vec<N> dv = Vec<N>::Zero();
  double decay_v = 1.0, decay_w = 1.0;
  // Then what the position update reads and writes of it (integrate_substep_positions).
  // Soft step: where the body was when the step began, and how far it has moved and turned since
  // (the turn as a matrix, dq = R R0^-1), so the sub-steps see each contact's current separation.
  Vec<N> x0 = Vec<N>::Zero();
  Mat<N> r0_inverse = Mat<N>::Identity();
  Vec<N> dp = Vec<N>::Zero();
  Mat<N> dq = Mat<N>::Identity();
};

// A body's inverse mass and inertia in this step (load_solver_bodies, build.cpp), 0 for one that does
// not move: what forming effective masses and applying impulses outside the soft step's lanes read
// (ContactState::masses).
template <int N>
struct BodyMass {
  double inv_mass = 0.0;
  // The inverse inertia is iso_inv_inertia times the identity in every frame (a body whose inertia is
  // the same about every plane: a cube, a ball). The impulse passes then scale r ^ j instead of
  // multiplying it by the matrix, and inv_inertia is that exactly.
  bool isotropic = false;
  double iso_inv_inertia = 0.0;
  BivMat<N> inv_inertia = BivMat<N>::Zero();  // world frame
};

// What the paper's solver keeps of a body beside its SolverBody (PaperSolver::bodies).
template <int N>
struct PaperBody {
  Vec<N> vp = Vec<N>::Zero();  // pseudo velocity (split impulse): moves the position this step, then is dropped
  Bivector<N> wp{};
  int level = 0;               // contact-graph level (shock propagation)
  std::uint64_t moved = 0;     // shock propagation: the visit that last changed its velocity beyond tolerance
};

// One contact point: lever arms, what it needs of K = delta/m + [r]_*^T I^-1 [r]_* (summed over the
// bodies that can move), the effective masses along the normal and in the tangent space, and the
// accumulated impulses of the current stage.
template <int N>
struct PointConstraint {
  // (The soft step builds no PointConstraints: its points go straight into the lanes, wide.hpp and
  // build_wide in build.cpp; fill_wide packs these the same way, for the tests. After the last
  // sub-step the lanes' impulses go to the pairs: unpack_wide.)
  double separation = 0.0;       // m, soft step: the separation when the step began (the lanes follow it)
  double normal_mass = 0.0;      // 1 / (n^T K n), of the bodies that can move
  double normal_impulse = 0.0;   // N s, accumulated in the current stage
  double normal_total = 0.0;     // N s, over all stages (events, ContactInfo)
  // Soft step: the normal's rows of the Jacobian, n . (r . w) = jn . w, and the angular velocity change
  // per unit normal impulse, I^-1 jn (the normal passes need no more of ra, rb; restitution reads them;
  // the lanes keep I^-1 jn only for non-isotropic bodies, and form it from jn for the rest).
  Eigen::Matrix<double, kBiv<N>, 1> jn_a = Eigen::Matrix<double, kBiv<N>, 1>::Zero(), jn_b = jn_a, dn_a = jn_a,
                                    dn_b = jn_a;
  // Friction (and both passes of the paper's solver).
  double friction = 0.0;  // the coefficient in use: static if the point was not slipping at the start
  bool sliding = false;   // it was slipping: kinetic friction, against the slip
  Vec<N> tangent_impulse = Vec<N>::Zero();          // N s, accumulated in the current stage
  Vec<N> slip_direction = Vec<N>::Zero();  // unit, the tangential slip when the step began (if sliding)
  Vec<N> ra = Vec<N>::Zero(), rb = Vec<N>::Zero();  // m, from the centres of mass
  // (P K P + n n^T)^-1 with P = 1 - n n^T: maps a tangential velocity change to the tangential impulse
  // that makes it (of the pair, or of the unfrozen body during shock propagation).
  Mat<N> tangent_mass = Mat<N>::Zero();
  // K n, of the bodies that can move (the pair's, or the unfrozen body's in shock propagation): how a
  // friction impulse j_t changes the normal velocity, n . K j_t = (K n) . j_t.
  Vec<N> kn = Vec<N>::Zero();
  double gap = 0.0;                                 // m, -depth at the start of the step
  double approach = 0.0;                            // m/s, normal velocity at the start (< 0 closing)
  double warm_normal = 0.0;                         // N s, last step's contact-stage impulses (warm start)
  Vec<N> warm_tangent = Vec<N>::Zero();
  double base_separation = 0.0;  // m, soft step: gap - n . (rb - ra), so that the current separation is
                                 // base + n . (dp_b + dq_b rb - dp_a - dq_a ra)
  double pseudo = 0.0;                              // split impulse along the normal
  double pseudo_mass = 0.0;                         // 1 / (n^T K n) of the pair (kept through shock propagation)
};

// What the soft step's lanes take of a point's effective masses and Jacobian (the rest of its lanes come
// from its LanePoint, lane_fill.hpp): formed from K, or, for a recycled pair of isotropic bodies, the last step's
// (SoftSolver::point_masses, Pair::points_first and built). 2D keeps the tangent mass along t alone (wide.hpp).
template <int N>
struct PointMasses {
  using Biv = Eigen::Matrix<double, kBiv<N>, 1>;
  using Tangent = std::conditional_t<N == 2, double, Mat<N>>;
  double normal_mass = 0.0;
  Biv jn_a = Biv::Zero(), jn_b = Biv::Zero();
  Tangent tangent_mass = zero_tangent();

 private:
  static Tangent zero_tangent() {
    if constexpr (N == 2) {
      return 0.0;
    } else {
      return Mat<N>::Zero();
    }
  }
};

// The effective masses of K for a contact with normal n.
// A point whose K is not finite and positive (a lever arm from a broken manifold point) gets zero
// effective masses, so it never receives an impulse instead of turning the bodies' velocities to NaN.
// (P: a PointConstraint, or anything with its kn, normal_mass and tangent_mass.)
template <int N, class P>
inline void set_effective_masses(P& p, const Mat<N>& k, const Vec<N>& n) {
  p.kn = k * n;
  p.normal_mass = 1.0 / n.dot(p.kn);
  const Mat<N> proj = Mat<N>::Identity() - n * n.transpose();
  p.tangent_mass = linalg::inverse<N>(Mat<N>(proj * k * proj + n * n.transpose()));
  if (!(std::isfinite(p.normal_mass) && p.normal_mass >= 0.0) || !all_finite(p.tangent_mass)) {
    p.normal_mass = 0.0;
    p.tangent_mass.setZero();
    p.kn.setZero();
  }
}

template <int N>
struct Constraint {
  int pair = 0;   // index into pairs
  int a = 0, b = 0;
  Vec<N> normal = Vec<N>::Zero();
  double friction = 0.0, kinetic_friction = 0.0, restitution = 0.0;
  int first = 0, count = 0;  // points[first .. first + count)
  int level = 0;             // max of the bodies' levels (shock propagation order)
  std::uint64_t shock_tick = 0;  // shock propagation: its last visit (see SolverBody::moved)
  double shock_change = 0.0;     // m/s, the largest normal velocity change of that visit
};

// A grab slot: the definition, and what the current step derived from it (see wedge/grab.hpp).
template <int N>
struct GrabConstraint {
  GrabDef<N> def;
  std::uint32_t generation = 0;
  bool live = false;
  bool active = false;                       // live, on an awake dynamic body, in this step
  double inv_mass = 0.0;                     // 1/kg, the body's in this step
  Vec<N> r = Vec<N>::Zero();                 // m, grab point from the centre of mass (world)
  Eigen::Matrix<double, kBiv<N>, N> w = Eigen::Matrix<double, kBiv<N>, N>::Zero();  // I'^-1 [r]_*
  Mat<N> mass = Mat<N>::Zero();              // K^-1
  Vec<N> bias = Vec<N>::Zero();              // m/s, bias_rate C
  double mass_scale = 0.0, impulse_scale = 0.0, max_impulse = 0.0;
  Vec<N> impulse = Vec<N>::Zero();           // N s, accumulated (kept between steps: warm start)
};

// The instruction set of the soft step's lane kernels (wide.hpp): 2-lane packs (SSE2, or NEON), or in
// 2D and 3D 4-lane packs on AVX2 or AVX-512 (the same packs, with twice the registers). All give the
// same bits.
enum class Lanes { Sse2, Avx2, Avx512 };
// The best the CPU has, unless the environment variable WEDGE_SIMD asks for less: "sse2", "avx2",
// "avx512" or "auto" (the default). A value the CPU cannot run, or any other value, is reported on
// stderr once and the best the CPU has is used.
Lanes default_lanes();
// Whether this CPU (and build) can run the lanes l.
bool lanes_supported(Lanes l);

// The state of each group of stages, owned by that group (the file named) and read by the others only
// where the comment says so. ContactState below holds one of each.

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

// The narrow phase (collide.cpp), and what continuous collision (continuous.cpp) reads of it.
template <int N>
struct NarrowPhase {
  std::vector<int> list;  // the pairs of one round
  // Per body: its transform and how fast any of its points moves (m/s), formed once per step instead
  // of once per pair side (a pyramid's box has up to six pairs).
  std::vector<Transform<N>> pose;
  std::vector<double> speed;
  // Per body, where the step began (continuous collision sweeps from there).
  std::vector<Vec<N>> start_center;
  std::vector<Rotor<N>> start_rotor;
  std::vector<unsigned char> wakes;  // per list entry: it touches a sleeping body
  std::vector<int> continuous_hits;  // continuous.cpp's scratch: the static bodies a swept body may reach
};

// The step's constraints (constraint_graph.cpp places them, build.cpp builds them): in pair order (the
// paper's solver) or colour order (soft step).
template <int N>
struct ConstraintGraph {
  std::vector<Constraint<N>> constraints;
  std::vector<int> constraint_pairs;         // the pairs that make them, in that order
  std::vector<std::uint32_t> colour_mask;    // per body: the colours its constraints took this step
  std::vector<int> colour_of, colour_order;  // colouring scratch (colour_order: the seeds in colour order)
  // Per constraint-to-be, in pair order: what colouring and placing its points need of its pair, read in
  // the one sweep over the pairs that finds them (the pairs are large, and read in colour order each
  // of their lines is a cache miss).
  // Colouring and the lanes are a function of the seeds alone (with which moving bodies are isotropic),
  // so a step whose seeds are the last step's keeps the last step's colours and lanes (graph_kept).
  struct Seed {
    int pair = 0;
    std::uint32_t a = 0, b = 0;
    int count = 0;
    bool move_a = false, move_b = false;
    bool iso_a = true, iso_b = true;  // the body is isotropic, or does not move
  };
  std::vector<Seed> seeds, previous_seeds;
  bool graph_kept = false;  // this step's constraints, colours and lanes are placed as the last step's
  // Soft step: where each colour's constraints begin, the uncoloured group's last, then the end (empty
  // for the paper's solver, whose constraints are in pair order).
  std::vector<int> colour_start;
  bool built_soft = false;   // the last step's constraints were the soft step's (previous_masses is theirs)
  std::uint64_t builds = 0;  // the builds so far, this step's included (Pair::built)
};

// The paper's solver (solver.cpp): the constraints' points (built by build.cpp; the tests pack the soft
// step's lanes from them too, fill_wide), shock propagation's order, the collision stage's energy terms.
template <int N>
struct PaperSolver {
  std::vector<PaperBody<N>> bodies;  // per body, set afresh by load_solver_bodies (build.cpp)
  std::vector<PointConstraint<N>> points;
  std::vector<int> shock_order;                 // constraints sorted by level (stable)
  std::vector<int> level_start, shock_scratch;  // its counting sort's buffers
  std::vector<double> group_b, group_c;         // collision-stage energy terms per group
  std::vector<char> group_driven;               // per group root: holds a grabbed body (no energy limit)
};

// The soft step (soft_step.cpp; build.cpp writes its lanes): the constraints in lanes (wide.hpp), colour
// by colour, and the sub-steps' bookkeeping.
template <int N>
struct SoftSolver {
  // What a recycled pair's points keep, this step's and the last (Pair::points_first, built): the
  // build writes points straight into the lanes and keeps no PointConstraints.
  std::vector<PointMasses<N>> point_masses, previous_masses;
  std::vector<WideConstraint<N>> wide;
  std::vector<WidePoint<N>> wide_points;
  std::vector<WidePointCold<N>> wide_cold;  // beside wide_points
  std::vector<Wide<N>> wide_approach;       // beside wide_points: m/s, the normal velocity at the start (restitution)
  std::vector<WideInertia<N>> wide_inertia;
  std::vector<int> wide_start, wide_scratch;  // wide_start: as ConstraintGraph::colour_start
  Lanes lanes = default_lanes();  // the lane kernels' instruction set (the same bits either way)
  double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;  // the contact spring
  int substep = 0;  // the sub-steps begun in this step
  // The relax pass's velocity changes are still to join warm_v (add_pass_change), in the next
  // sub-step's first sweep over the bodies (solve_substep), or integrate_velocities_apart's.
  bool pass_change_pending = false;
  // The solve pass's finish (finish_pass: its changes to warm_v, then v0 = v) is still to be done, by
  // integrate_substep_positions as it moves each body, or by the relax pass first.
  bool solve_finish_pending = false;
  std::vector<int> integrate_apart;  // moving bodies whose velocities integrate_velocities_apart integrates
};

// Islands and sleep (islands.cpp), per body; every stage reads `awake`, and wakes through wake_island.
struct Islands {
  std::vector<char> awake;
  std::vector<double> sleep_time;  // s spent below the sleep speed
  std::vector<int> island;         // label (smallest body index) of the island the body was last in, or -1
  std::vector<int> union_parent, bfs_queue, adjacency_start, adjacency;

  void wake(int i) {
    awake[i] = 1;
    sleep_time[i] = 0.0;
  }
  // Wakes the body and the island it fell asleep with.
  void wake_island(int i) {
    const int label = island[i];
    wake(i);
    if (label < 0) return;
    for (std::size_t j = 0; j < island.size(); ++j)
      if (island[j] == label && !awake[j]) wake(int(j));
  }
};

// The contact events (events.cpp).
template <int N>
struct Events {
  std::vector<ContactBeginEvent<N>> begin;
  std::vector<ContactEndEvent> end, ended;  // ended: pairs dropped by the broad phase this step (pairs.cpp)
};

// Everything the contact stages keep between and during steps: each group's state, the solver's copies
// of the bodies, which every stage reads, and the grabs.
template <int N>
struct ContactState {
  PairList<N> list;
  NarrowPhase<N> narrow;
  ConstraintGraph<N> graph;
  PaperSolver<N> paper;
  SoftSolver<N> soft;
  Islands islands;
  Events<N> events;
  std::vector<SolverBody<N>> solver_bodies;  // per body (build.cpp loads them)
  std::vector<BodyMass<N>> masses;           // per body (likewise)
  std::vector<GrabConstraint<N>> grabs;      // slots, solved in slot order (grab.cpp)
  std::vector<char> driven;                  // per body: held by an active grab this step
  parallel::Workers workers;                 // WorldSettings::workers, set by World::step
};

// The fewest items a thread takes when a loop is split: below this the hand-over costs more than the
// work (about a microsecond; a body update or a constraint visit takes 20-200 ns).
constexpr int kBodyGrain = 128;
constexpr int kConstraintGrain = 32;
constexpr int kPointGrain = 64;  // solver passes: a point visit takes 10-60 ns

// fn(i) for every body, split over the workers.
template <int N, class F>
void for_each_body(ContactState<N>& s, int count, F&& fn) {
  s.workers.for_ranges(count, kBodyGrain, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) fn(i);
  });
}
// fn(constraint) for every constraint, each touching only its own points and pair (any order).
template <int N, class F>
void for_each_constraint(ContactState<N>& s, F&& fn) {
  s.workers.for_ranges(int(s.graph.constraints.size()), kConstraintGrain, [&](int begin, int end) {
    for (int k = begin; k < end; ++k) fn(s.graph.constraints[k]);
  });
}
// fn(begin, end) over items[first, last) (constraints, or wide constraints), each with first and count
// into its points: the whole range on this thread, or, where each thread gets at least kPointGrain
// points (a wide constraint's slot counting as `lanes`), one range per thread of equal shares of the
// points, cut at items.
template <class Item, class F>
void for_shares(parallel::Workers& workers, const std::vector<Item>& items, int first, int last, int lanes, F&& fn) {
  const int begin_point = items[first].first, end_point = items[last - 1].first + items[last - 1].count;
  const int parts = std::min(workers.count(), (end_point - begin_point) * lanes / kPointGrain);
  if (parts <= 1) {
    fn(first, last);
    return;
  }
  workers.for_parts(parts, [&](int part, int of) {
    const auto cut = [&](int i) {
      if (i == of) return last;
      const int target = begin_point + int(std::int64_t(end_point - begin_point) * i / of);
      return int(std::lower_bound(items.begin() + first, items.begin() + last, target,
                                  [](const Item& c, int t) { return c.first < t; }) -
                 items.begin());
    };
    fn(cut(part), cut(part + 1));
  });
}
template <int N>
using Shapes = std::vector<std::shared_ptr<const Shape<N>>>;

// recycling.cpp: keep a pair's manifold while the bodies have moved and turned relative to each other by
// less than the recycle tolerance since it was computed (only separations are updated), or else note the
// state a fresh manifold was computed in. ra, rb: the bodies' rotation matrices now.
template <int N>
bool recycle_manifold(Pair<N>& pair, const Body<N>& a, const Body<N>& b, const Mat<N>& ra, const Mat<N>& rb,
                      double extent, const ContactSettings& settings);
template <int N>
void cache_manifold(Pair<N>& pair, const Body<N>& a, const Body<N>& b, const Mat<N>& ra, const Mat<N>& rb);
// find_contacts.cpp: the stages below, in order. (profile, if given, takes the broad phase's, the
// narrow phase's and the constraints' times.) A body's material must stay the same from step to step,
// as World's do: a step that finds the last step's constraints keeps their mixed friction and
// restitution (build_wide).
template <int N>
void find_contacts(ContactState<N>& state, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                   const std::vector<Material>& materials, const ContactSettings& settings, double h,
                   StepProfile* profile = nullptr);
// pairs.cpp: a new body's proxy and box; each step, the moving bodies' proxies moved and the candidate
// pairs merged into the sorted pair list (a pair that leaves while touching ends: `ended`).
template <int N>
void add_body(ContactState<N>& state, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, int index);
template <int N>
void update_pairs(ContactState<N>& state, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, double h);
// collide.cpp: every pair with an awake dynamic body (or a moving kinematic one) gets this step's
// manifold; the sleeping islands it touches are woken, and their pairs collided in turn.
template <int N>
void collide_pairs(ContactState<N>& state, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                   const ContactSettings& settings, double h);
// build.cpp: the solver bodies from the bodies (velocities, inverse masses, world inverse inertias;
// soft: the bodies that do not move frozen), then the constraints and their points.
template <int N>
void load_solver_bodies(ContactState<N>& state, const std::vector<Body<N>>& bodies, bool soft);
template <int N>
void build_constraints(ContactState<N>& state, const std::vector<Body<N>>& bodies,
                       const std::vector<Material>& materials, const ContactSettings& settings);
// constraint_graph.cpp: this step's seeds (a pair with points and a body that moves), and unless they
// are the last step's (graph_kept), the constraints' places: colours and lanes for the soft step.
template <int N>
void update_constraint_graph(ContactState<N>& state, const std::vector<Body<N>>& bodies, bool soft);
// events.cpp
template <int N>
void report_events(ContactState<N>& state);
// continuous.cpp: after the solver, each fast dynamic body swept against the static shapes on its way,
// and put back where it would first reach one (ContactSettings::continuous).
template <int N>
void solve_continuous(ContactState<N>& state, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                      const std::vector<Material>& materials, const ContactSettings& settings, double h);
// solver.cpp
template <int N>
void process_collisions(ContactState<N>& state, std::vector<Body<N>>& bodies, const ContactSettings& settings,
                        double h);
template <int N>
void process_contacts(ContactState<N>& state, std::vector<Body<N>>& bodies, const ContactSettings& settings,
                      double h);
// The paper's position update: every awake body moved by its velocities and the pseudo velocities of
// process_contacts' position correction over h (and, when repair_now, its rotor repaired).
template <int N>
void integrate_positions(ContactState<N>& state, std::vector<Body<N>>& bodies, double h, bool repair_now);
// grab.cpp: derive the step's grab data (and `driven`), apply last step's impulses, one pass. The pass
// returns the largest velocity change it made (m/s), for the solver's early exit.
template <int N>
bool prepare_grabs(ContactState<N>& state, const std::vector<Body<N>>& bodies, double h);
template <int N>
void warm_start_grabs(ContactState<N>& state);
template <int N>
double solve_grabs(ContactState<N>& state);
// soft_step.cpp: the SoftStep solver's stages. World::step runs prepare_soft_step, then per sub-step
// integrate_velocities_apart, solve_substep(use_bias = true) (the other bodies' velocity integration
// first, integrate_substep_velocity), integrate_substep_positions (with track_body_motion) and
// solve_substep(false), then finish_soft_step.
// prepare_soft_step: where each body starts (start_body_motion), its sub-steps' velocity integration
// from `motion` (without one, the tests', the velocities are not integrated: the caller changes them
// between sub-steps), then prepare_soft_contacts.
template <int N>
void prepare_soft_step(ContactState<N>& state, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                       double h, const dynamics::Motion<N>* motion = nullptr);
// The velocities of the bodies the solve sub-step cannot integrate itself (a torque, or a gyroscopic
// term), integrated from the bodies (dynamics::integrate_velocity).
template <int N>
void integrate_velocities_apart(ContactState<N>& state, const std::vector<Body<N>>& bodies,
                                const dynamics::Motion<N>& motion, double h);
// Every awake body moved by its solver body's velocities over h (and, when repair_now, its rotor repaired).
template <int N>
void integrate_substep_positions(ContactState<N>& state, std::vector<Body<N>>& bodies, double h, bool repair_now);
template <int N>
void prepare_soft_contacts(ContactState<N>& state, const ContactSettings& settings, double h);
// Where a body starts the soft step, for its motion since (track_body_motion).
template <int N>
inline void start_body_motion(SolverBody<N>& sb, const Body<N>& body) {
  sb.x0 = body.center;
  sb.r0_inverse = to_matrix(body.rotor).transpose();
  sb.dp.setZero();
  sb.dq.setIdentity();
}
template <int N>
void solve_substep(ContactState<N>& state, std::vector<Body<N>>& bodies, const ContactSettings& settings,
                   double h, bool use_bias);
template <int N>
void track_substep_motion(ContactState<N>& state, const std::vector<Body<N>>& bodies);
// The relax pass's velocity changes added to warm_v now, in a sweep of their own, for a caller that
// changes the solver bodies' velocities between sub-steps itself (the tests; integrate_velocities_apart
// adds those of the bodies it integrates, and solve_substep the rest).
template <int N>
void flush_pass_change(ContactState<N>& state);
// One body's part of it: how far it has moved (dp) and turned (dq = R R0^-1) since the step began, for
// the relax pass's separations. integrate_substep_positions calls it for each body it moves, in the
// same sweep, rather than in a sweep of its own over every body per sub-step.
template <int N>
inline void track_body_motion(SolverBody<N>& sb, const Body<N>& body) {
  sb.dp = body.center - sb.x0;
  sb.dq = to_matrix(body.rotor) * sb.r0_inverse;
}
// A body's velocity integration in a sub-step (dynamics::integrate_velocity's arithmetic, from the step's
// constants): the solve sub-step runs it in its first sweep over the bodies. Through the sub-steps the
// velocities live in the solver bodies alone; finish_soft_step stores them to the bodies.
// The soft step's warm start, body by body (soft_step.cpp, warm_start_substep): after a contact pass
// that began with snapshot_velocities, what it changed of a body's velocities is added to warm_v and
// warm_w (add_pass_change; the first sub-step's point-by-point warm start sets them, set_warm_start),
// and the next sub-step adds them to the fresh velocities (add_warm_start). A frozen body takes none.
template <int N>
inline void add_pass_change(SolverBody<N>& b) {
  if (b.frozen) return;
  b.warm_v = b.warm_v + (b.v - b.v0);
  b.warm_w = b.warm_w + (b.w - b.w0);
}
// One body's part of finish_pass (soft_step.cpp): the solve pass's changes to the warm start, then the
// velocities as the relax pass will find them.
template <int N>
inline void finish_body_pass(SolverBody<N>& b) {
  add_pass_change(b);
  b.v0 = b.v;
  b.w0 = b.w;
}
template <int N>
inline void integrate_substep_velocity(SolverBody<N>& b) {
  if (!b.integrates) return;
  b.v += b.dv;
  b.v *= b.decay_v;
  b.w *= b.decay_w;
}
template <int N>
void finish_soft_step(ContactState<N>& state, std::vector<Body<N>>& bodies, const ContactSettings& settings);
// The step's colour-ordered constraints into lanes (wide.hpp): assign_lanes gives each a lane (within a
// colour by point count, most first, kLanes to a wide constraint; the uncoloured group one to a wide
// constraint, in order) from the constraints' bodies and point counts alone. find_contacts then builds
// each point straight into its lane (build.cpp, build_wide). fill_wide does the same from points built
// as PointConstraints and prepared (prepare_points: the step's separations and warm-start impulses),
// through the same writes (lane_fill.hpp), and pack_wide for all at once: the tests' reference.
template <int N>
void assign_lanes(ContactState<N>& state);
template <int N>
void fill_wide(ContactState<N>& state, WideConstraint<N>& wide);
template <int N>
void prepare_points(ContactState<N>& state, const Constraint<N>& constraint, bool warm_start);
template <int N>
void pack_wide(ContactState<N>& state);
// One solve (use_bias) or relax pass of the contacts over the packed lanes, and the lanes' impulses to
// the pairs (warm_normal, warm_tangent, and the totals in normal_impulse; run by solve_substep and
// finish_soft_step; declared for the tests). count_warm_start:
// each point's normal_total first takes its accumulated impulse, which the sub-step's warm start applied
// body by body without visiting the point.
template <int N>
void solve_contacts(ContactState<N>& state, const ContactSettings& settings, double h, bool use_bias,
                    bool count_warm_start = false);
template <int N>
void unpack_wide(ContactState<N>& state);
// islands.cpp
template <int N>
void compute_levels(ContactState<N>& state, const std::vector<Body<N>>& bodies);
template <int N>
void update_islands(ContactState<N>& state, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h);

// A body the solvers move: dynamic and awake. Static, kinematic and sleeping bodies are only read.
template <int N>
inline bool moves(const ContactState<N>& s, const std::vector<Body<N>>& bodies, std::size_t i) {
  return bodies[i].is_dynamic() && s.islands.awake[i];
}

// Kinematic bodies with a velocity can hit sleeping bodies and keep them awake; resting ones behave
// like static bodies.
template <int N>
inline bool moving_kinematic(const Body<N>& b) {
  return b.type == BodyType::Kinematic && (b.velocity.squaredNorm() > 0.0 || b.angular_velocity.c.squaredNorm() > 0.0);
}

// I^-1 t for a bivector t (world frame): a scale for an isotropic body.
template <int N>
inline Eigen::Matrix<double, kBiv<N>, 1> inverse_inertia_times(const BodyMass<N>& b,
                                                               const Eigen::Matrix<double, kBiv<N>, 1>& t) {
  if (b.isotropic) return b.iso_inv_inertia * t;
  return b.inv_inertia * t;
}
// The change of the body's angular velocity per impulse j at lever arm r: I^-1 (r ^ j). Formed here
// rather than kept per point as the k x N matrix I^-1 [r]_*, which would be most of a point's size;
// for an isotropic body it is a scale.
template <int N>
inline Eigen::Matrix<double, kBiv<N>, 1> angular_change(const BodyMass<N>& b, const Vec<N>& r, const Vec<N>& j) {
  return inverse_inertia_times(b, outer<N>(r, j).c);
}

// The body's part of K = delta/m + [r]_*^T I^-1 [r]_* without the 1/m: [r]_*^T I^-1 [r]_*, which for an
// isotropic body is s (|r|^2 1 - r r^T) (r . (r ^ a) = |r|^2 a - (r . a) r).
template <int N>
inline Mat<N> angular_mass_term(const BodyMass<N>& b, const Vec<N>& r) {
  if (b.isotropic) return b.iso_inv_inertia * (r.squaredNorm() * Mat<N>::Identity() - r * r.transpose());
  const WedgeMat<N> jr = wedge_matrix<N>(r);
  return jr.transpose() * (b.inv_inertia * jr);
}

// Relative velocity of b with respect to a at the point: (v_b + r_b . w_b) - (v_a + r_a . w_a).
template <int N, class P>  // (P: a PointConstraint, or anything with its lever arms ra, rb)
inline Vec<N> relative_velocity(const SolverBody<N>& a, const SolverBody<N>& b, const P& p) {
  return b.v + dot<N>(p.rb, b.w) - a.v - dot<N>(p.ra, a.w);
}

}  // namespace wedge::contact
