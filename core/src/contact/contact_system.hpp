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
// Grabs (grab.cpp) are solved inside process_contacts, before the contacts in every pass; in the soft
// step, grabs and then joints (joints.cpp) before the contacts in each pass of each sub-step.
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

#include "wedge/body.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/detail/broadphase.hpp"
#include "wedge/contact.hpp"
#include "wedge/grab.hpp"
#include "wedge/profile.hpp"
#include "contact/constraint.hpp"
#include "contact/joint.hpp"
#include "contact/pair.hpp"
#include "contact/solver_body.hpp"
#include "contact/wide.hpp"
#include "dynamics/integrate.hpp"
#include "parallel/workers.hpp"

namespace wedge::dynamics {
template <int N>
struct Motion;  // dynamics/integrate.hpp
}  // namespace wedge::dynamics

namespace wedge::contact {

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
// where the comment says so. ContactState below holds one of each: PairList (pair.hpp),
// ConstraintGraph (constraint.hpp) and the groups below; the solver bodies are in solver_body.hpp.

// The narrow phase (collide.cpp), and what continuous collision (continuous.cpp) reads of it.
template <int N>
struct NarrowPhase {
  std::vector<int> list;  // the pairs of one round
  // Per body: its transform and how fast any of its points moves (m/s), formed once per step instead
  // of once per pair side (a pyramid's box has up to six pairs).
  std::vector<Transform<N>> pose;  // (only of bodies in a pair collided this step: posed)
  std::vector<char> posed;
  std::vector<int> unposed;        // collide.cpp's scratch: the bodies whose poses a round still needs
  std::vector<double> speed;
  // Per body, where the step began (continuous collision sweeps from there).
  std::vector<Vec<N>> start_center;
  std::vector<Rotor<N>> start_rotor;
  std::vector<unsigned char> wakes;  // per list entry: it touches a sleeping body
  std::vector<int> continuous_hits;  // continuous.cpp's scratch: the static bodies a swept body may reach
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
  std::vector<int> alone;            // the bodies integrate_alone moves (SolverBody::alone)
  std::vector<dynamics::AngularModel<N>> angular_models;  // per body: theirs, found once per step
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

// The joints (joints.cpp; World adds and removes them): slots, solved in slot order.
template <int N>
struct JointSolver {
  std::vector<JointConstraint<N>> slots;
  // The joined pairs whose bodies do not collide (JointBodies::collide_connected false), as sorted keys
  // (a << 32 | b, a < b), which the pair list leaves out (pairs.cpp). World keeps it.
  std::vector<std::uint64_t> no_collide;
  // The removed joints' slots, a min-heap: World::add_joint takes the lowest (a fixed, replayable order)
  // without scanning the slots (World keeps it).
  std::vector<std::uint32_t> free_slots;
  bool any_active = false;  // this step: some joint acts (prepare_joints)
  double h = 0.0;           // s, the sub-step prepare_joints last prepared for (the reaction forces)
  Softness soft;            // the joints' error correction (their angular rows': turn_soft) in that step's sub-steps
  Softness turn_soft;
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
  std::vector<char> inertia_used;            // per body: a constraint or a grab uses its masses this step
  std::vector<GrabConstraint<N>> grabs;      // slots, solved in slot order (grab.cpp)
  std::vector<char> driven;                  // per body: held by an active grab this step
  JointSolver<N> joints;
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
// joints.cpp (soft step only): at a step's first sub-step, every live joint's effective masses from the
// bodies' poses (true if one acts; later sub-steps return that); each sub-step, each joint placed (lever
// arms and error from the poses now) and its accumulated impulses applied, then one pass (use_bias: the
// solve pass, else the relax pass, which places it again). joint_impulse: the accumulated impulse on
// body b (N s, world); joint_angle_now: a revolute joint's angle at the bodies' poses now (rad).
template <int N>
bool prepare_joints(ContactState<N>& state, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                    double h);
template <int N>
void warm_start_joints(ContactState<N>& state, const std::vector<Body<N>>& bodies);
template <int N>
void solve_joints(ContactState<N>& state, const std::vector<Body<N>>& bodies, bool use_bias);
template <int N>
double joint_angle_now(const JointConstraint<N>& joint, const std::vector<Body<N>>& bodies);
template <int N>
Vec<N> joint_impulse(const JointConstraint<N>& joint);
// The accumulated turn impulse on body b (N m s, world; zero for point and distance joints).
template <int N>
Bivector<N> joint_turn_impulse(const JointConstraint<N>& joint);
// soft_step.cpp: the SoftStep solver's stages. World::step runs prepare_soft_step, then per sub-step
// integrate_velocities_apart, solve_substep(use_bias = true) (the other bodies' velocity integration
// first, integrate_substep_velocity), integrate_substep_positions (with track_body_motion) and
// solve_substep(false), then integrate_alone and finish_soft_step.
// prepare_soft_step: where each body starts (start_body_motion), which bodies are alone, its sub-steps'
// velocity integration from `motion` (without one, the tests', the velocities are not integrated and no
// body is alone: the caller changes them between sub-steps), then prepare_soft_contacts.
template <int N>
void prepare_soft_step(ContactState<N>& state, const std::vector<Body<N>>& bodies, const ContactSettings& settings,
                       double h, const dynamics::Motion<N>* motion = nullptr);
// The velocities of the bodies the solve sub-step cannot integrate itself (a torque, or a gyroscopic
// term), integrated from the bodies (dynamics::integrate_velocity).
template <int N>
void integrate_velocities_apart(ContactState<N>& state, const std::vector<Body<N>>& bodies,
                                const dynamics::Motion<N>& motion, double h);
// Every awake body moved by its solver body's velocities over h (and, when repair_now, its rotor repaired).
// The bodies alone are integrate_alone's.
template <int N>
void integrate_substep_positions(ContactState<N>& state, std::vector<Body<N>>& bodies, double h, bool repair_now);
// The bodies alone (SolverBody::alone: no constraint or grab uses them this step) through all the step's
// `substeps` sub-steps of h, body by body: velocities, then positions, and when repair_at_end the rotor
// repaired after the last (dynamics::advance_alone). Between the sub-steps nothing reads or changes such
// a body, so its sub-steps can be taken together, its angular velocity in the body frame throughout.
template <int N>
void integrate_alone(ContactState<N>& state, std::vector<Body<N>>& bodies, const dynamics::Motion<N>& motion,
                     double h, int substeps, bool repair_at_end);
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

}  // namespace wedge::contact
