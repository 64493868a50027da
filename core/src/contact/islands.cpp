// The contact graph: its levels upward from static bodies (for shock propagation) and its islands of
// touching dynamic bodies (for sleeping). Breadth-first search and union-find over the step's
// constraints, in constraint order, so both are deterministic.
#include <algorithm>
#include <limits>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

constexpr int kUnreached = std::numeric_limits<int>::max();

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Union keeping the smaller index as the root, so a label is the island's smallest body index.
void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a == b) return;
  if (a < b)
    parent[b] = a;
  else
    parent[a] = b;
}

}  // namespace

// Level -1: static, kinematic and sleeping bodies (infinite mass in this step). Level 0: dynamic bodies
// touching one of them; level k + 1: touching a level-k body. Bodies that no chain reaches (a free
// cluster in the air) keep kUnreached and are left out of shock propagation.
template <int N>
void compute_levels(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  const int n = int(bodies.size());
  auto movable = [&](int i) { return moves(s, bodies, std::size_t(i)); };
  for (int i = 0; i < n; ++i) s.paper.bodies[i].level = movable(i) ? kUnreached : -1;
  // Adjacency between movable bodies (compressed rows).
  s.islands.adjacency_start.assign(n + 1, 0);
  for (const Constraint<N>& c : s.graph.constraints)
    if (movable(c.a) && movable(c.b)) {
      ++s.islands.adjacency_start[c.a + 1];
      ++s.islands.adjacency_start[c.b + 1];
    }
  for (int i = 0; i < n; ++i) s.islands.adjacency_start[i + 1] += s.islands.adjacency_start[i];
  s.islands.adjacency.resize(s.islands.adjacency_start[n]);
  s.islands.bfs_queue.assign(s.islands.adjacency_start.begin(), s.islands.adjacency_start.end() - 1);  // fill cursors
  for (const Constraint<N>& c : s.graph.constraints)
    if (movable(c.a) && movable(c.b)) {
      s.islands.adjacency[s.islands.bfs_queue[c.a]++] = c.b;
      s.islands.adjacency[s.islands.bfs_queue[c.b]++] = c.a;
    }
  s.islands.bfs_queue.clear();
  for (const Constraint<N>& c : s.graph.constraints) {
    const bool ma = movable(c.a), mb = movable(c.b);
    if (ma == mb) continue;
    const int i = ma ? c.a : c.b;
    if (s.paper.bodies[i].level == kUnreached) {
      s.paper.bodies[i].level = 0;
      s.islands.bfs_queue.push_back(i);
    }
  }
  for (std::size_t head = 0; head < s.islands.bfs_queue.size(); ++head) {
    const int i = s.islands.bfs_queue[head];
    for (int e = s.islands.adjacency_start[i]; e < s.islands.adjacency_start[i + 1]; ++e) {
      const int j = s.islands.adjacency[e];
      if (s.paper.bodies[j].level == kUnreached) {
        s.paper.bodies[j].level = s.paper.bodies[i].level + 1;
        s.islands.bfs_queue.push_back(j);
      }
    }
  }
  s.paper.shock_order.clear();
  for (std::size_t ci = 0; ci < s.graph.constraints.size(); ++ci) {
    Constraint<N>& c = s.graph.constraints[ci];
    c.level = std::max(s.paper.bodies[c.a].level, s.paper.bodies[c.b].level);
    if (c.level != kUnreached) s.paper.shock_order.push_back(int(ci));
  }
  // Stable counting sort by level, which is >= -1 (std::stable_sort would allocate a buffer every step).
  int top = -1;
  for (int ci : s.paper.shock_order) top = std::max(top, s.graph.constraints[ci].level);
  auto bin = [&s](int ci) { return std::size_t(s.graph.constraints[ci].level + 1); };
  s.paper.level_start.assign(std::size_t(top + 3), 0);
  for (int ci : s.paper.shock_order) ++s.paper.level_start[bin(ci) + 1];
  for (std::size_t l = 1; l < s.paper.level_start.size(); ++l) s.paper.level_start[l] += s.paper.level_start[l - 1];
  s.paper.shock_scratch.resize(s.paper.shock_order.size());
  for (int ci : s.paper.shock_order) s.paper.shock_scratch[std::size_t(s.paper.level_start[bin(ci)]++)] = ci;
  s.paper.shock_order.swap(s.paper.shock_scratch);
}

// Islands: dynamic bodies joined by contact points or joints. A body is still while its centre and the rim of its
// bounding sphere move slower than sleep_linear_speed (and no moving kinematic body touches it); an
// island whose bodies have all been still for time_to_sleep falls asleep, velocities set to zero.
template <int N>
void update_islands(ContactState<N>& s, std::vector<Body<N>>& bodies, const ContactSettings& settings, double h) {
  // Sleeping off: nothing would read the islands (Box2D v3 skips its island work likewise). The rest
  // timers restart, so that turning sleep on does not put an
  // island to sleep for the rest it had while sleeping was off.
  if (!settings.allow_sleep) {
    std::fill(s.islands.sleep_time.begin(), s.islands.sleep_time.end(), 0.0);
    return;
  }
  const int n = int(bodies.size());
  auto movable = [&](int i) { return moves(s, bodies, std::size_t(i)); };
  s.islands.union_parent.resize(n);
  for (int i = 0; i < n; ++i) s.islands.union_parent[i] = i;
  for (int i = 0; i < n; ++i) {
    if (!movable(i)) continue;
    const Body<N>& b = bodies[i];
    // A body without a shape can never be touched awake again, so it never sleeps.
    if (s.list.proxy[i] < 0) {
      s.islands.sleep_time[i] = 0.0;
      continue;
    }
    const double radius = s.list.box[i].extents().norm();  // bounds the distance from the centre of mass
    const double speed = b.velocity.norm() + b.angular_velocity.c.norm() * radius;
    s.islands.sleep_time[i] = speed < settings.sleep_linear_speed ? s.islands.sleep_time[i] + h : 0.0;
  }
  for (const Constraint<N>& c : s.graph.constraints) {
    const bool ma = movable(c.a), mb = movable(c.b);
    if (ma && mb) {
      unite(s.islands.union_parent, c.a, c.b);
    } else {
      const int other = ma ? c.b : c.a, self = ma ? c.a : c.b;
      if (moving_kinematic(bodies[other])) s.islands.sleep_time[self] = 0.0;
    }
  }
  // Joined bodies sleep and wake together (a joint to a moving kinematic body keeps its body awake).
  for (const JointConstraint<N>& j : s.joints.slots) {
    if (!j.live || j.a < 0) continue;
    const bool ma = movable(j.a), mb = movable(j.b);
    if (ma && mb) {
      unite(s.islands.union_parent, j.a, j.b);
    } else if (ma != mb) {
      const int other = ma ? j.b : j.a, self = ma ? j.a : j.b;
      if (moving_kinematic(bodies[other])) s.islands.sleep_time[self] = 0.0;
    }
  }
  // Smallest sleep time per island, kept at its root.
  for (int i = 0; i < n; ++i) {
    if (!movable(i)) continue;
    const int r = find_root(s.islands.union_parent, i);
    s.islands.island[i] = r;
    if (r != i) s.islands.sleep_time[r] = std::min(s.islands.sleep_time[r], s.islands.sleep_time[i]);
  }
  for (int i = 0; i < n; ++i) {
    if (!movable(i) || s.islands.sleep_time[s.islands.island[i]] < settings.time_to_sleep) continue;
    s.islands.awake[i] = 0;
    bodies[i].velocity.setZero();
    bodies[i].angular_velocity = Bivector<N>{};
  }
}

#define WEDGE_INSTANTIATE(N)                                                     \
  template void compute_levels<N>(ContactState<N>&, const std::vector<Body<N>>&); \
  template void update_islands<N>(ContactState<N>&, std::vector<Body<N>>&, const ContactSettings&, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
