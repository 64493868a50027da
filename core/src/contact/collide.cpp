// The narrow phase of the contact stages: each pair that an awake body takes part in gets this step's
// manifold, recycled (recycling.cpp) or collided afresh with the speculative margin, and the sleeping
// islands such a manifold touches are woken (and their pairs collided in turn).
#include <algorithm>

#include "contact/contact_system.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

template <int N>
Transform<N> transform_of(const Body<N>& b) {
  return Transform<N>{b.position(), to_matrix(b.rotor)};
}

// Shapes whose contact points stay put on their faces while they touch (see recycling.cpp).
template <int N>
bool flat_faced(const Shape<N>& shape) {
  return shape.features() != nullptr || !shape.bounded();
}

// An upper bound of how fast any point of the body moves (m/s): centre speed plus |w| times the radius
// of the sphere about the centre of mass that holds its bounding box (at most the box's diagonal). Zero
// for a half-space (static).
template <int N>
double speed_bound(const ContactState<N>& s, const Body<N>& b, int i) {
  if (s.list.proxy[i] < 0) return 0.0;
  return b.velocity.norm() + b.angular_velocity.c.norm() * s.list.box[i].extents().norm();
}

// One pair's manifold: recycled while the bodies barely move relative to each other, else collided with
// the speculative margin (below). Reads the bodies, writes only the pair.
// (flatten: the bodies' rotation matrices and the recycling test are inlined into it.)
template <int N>
[[gnu::flatten]] void collide_pair(const ContactState<N>& s, Pair<N>& p, const std::vector<Body<N>>& bodies,
                                   const Shapes<N>& shapes, const ContactSettings& settings, double h) {
  const Body<N>& a = bodies[p.a];
  const Body<N>& b = bodies[p.b];
  const double reach = h * (s.narrow.speed[p.a] + s.narrow.speed[p.b]);
  CollisionSettings cs;
  cs.exact_separation = false;
  cs.face_preference = settings.face_preference;
  cs.contact_margin = settings.contact_margin + reach;
  const Transform<N>& ta = s.narrow.pose[p.a];
  const Transform<N>& tb = s.narrow.pose[p.b];
  // Recycled only between slow bodies (soft step): a fast one may meet new features within the step.
  const bool flat = settings.solver == ContactSolver::SoftStep && flat_faced(*shapes[p.a]) && flat_faced(*shapes[p.b]);
  // How far a point of a body that moves can be from its centre (0 for static bodies).
  const double extent = std::max(a.type == BodyType::Static ? 0.0 : s.list.radius[p.a],
                                 b.type == BodyType::Static ? 0.0 : s.list.radius[p.b]);
  p.recycled = flat && reach <= settings.recycle_distance &&
               recycle_manifold(p, a, b, ta.rotation, tb.rotation, extent, settings);
  if (!p.recycled) {
    p.manifold = collide(*shapes[p.a], ta, *shapes[p.b], tb, cs);
    cache_manifold(p, a, b, ta.rotation, tb.rotation);
    p.cached = flat;
  }
  p.updated = true;
}

// A pair's every cache line, requested ahead of its use: the narrow phase reads all of each pair (its
// manifold, and the recycling's state at the end), in pair order but past the hardware prefetcher's
// reach (a 2D pair is nine lines, of which it reads five or six).
constexpr int kPrefetchAhead = 4;
template <int N>
void prefetch_pair(const Pair<N>& p) {
  const char* bytes = reinterpret_cast<const char*>(&p);
  for (std::size_t at = 0; at < sizeof(Pair<N>); at += 64) __builtin_prefetch(bytes + at);
}

// The transforms of the bodies of this round's pairs that have none yet in this step (NarrowPhase::pose).
template <int N>
void pose_pairs_bodies(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  std::vector<int>& unposed = s.narrow.unposed;
  unposed.clear();
  for (const int pi : s.narrow.list) {
    const Pair<N>& p = s.list.pairs[pi];
    for (const std::uint32_t i : {p.a, p.b})
      if (!s.narrow.posed[i]) {
        s.narrow.posed[i] = 1;
        unposed.push_back(int(i));
      }
  }
  s.workers.for_ranges(int(unposed.size()), kBodyGrain, [&](int begin, int end) {
    for (int k = begin; k < end; ++k) s.narrow.pose[unposed[k]] = transform_of(bodies[unposed[k]]);
  });
}

}  // namespace

// Collides every pair with an awake dynamic body (or a moving kinematic one against a dynamic body).
// Each pair's margin is the speculative contact_margin plus how far the two can close in one step, so a
// contact that will close during the step is seen now (Guendelman's predicted positions, to first
// order). Each round collides the pairs needed now, split over the workers, then wakes the sleeping
// islands they touch, in pair order; the woken islands' pairs are collided in the next round.
template <int N>
void collide_pairs(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                   const ContactSettings& settings, double h) {
  auto active = [&](std::uint32_t i) { return moves(s, bodies, i); };
  auto sleeps = [&](std::uint32_t i) { return bodies[i].is_dynamic() && !s.islands.awake[i]; };
  // (Every body's: waking in a later round moves none. The poses only of the bodies in a pair collided,
  // pose_pairs_bodies: a body alone in the air needs none.)
  s.narrow.pose.resize(bodies.size());
  s.narrow.posed.assign(bodies.size(), 0);
  s.narrow.speed.resize(bodies.size());
  s.narrow.start_center.resize(bodies.size());
  s.narrow.start_rotor.resize(bodies.size());
  for_each_body(s, int(bodies.size()), [&](int i) {
    s.narrow.speed[i] = speed_bound(s, bodies[i], i);
    s.narrow.start_center[i] = bodies[i].center;
    s.narrow.start_rotor[i] = bodies[i].rotor;
  });
  for (bool again = true, first = true; again; first = false) {
    again = false;
    s.narrow.list.clear();
    for (std::size_t pi = 0; pi < s.list.pairs.size(); ++pi) {
      Pair<N>& p = s.list.pairs[pi];
      if (first) p.updated = false;  // (in the same sweep: the pairs are kilobytes)
      const Body<N>& a = bodies[p.a];
      const Body<N>& b = bodies[p.b];
      if (!p.updated && (active(p.a) || active(p.b) || (moving_kinematic(a) && b.is_dynamic()) ||
                         (moving_kinematic(b) && a.is_dynamic())))
        s.narrow.list.push_back(int(pi));
    }
    pose_pairs_bodies(s, bodies);
    // (Whether a pair touches a sleeping body is noted as it is collided, and only those pairs are
    // read again, in order, to wake: reading every pair again was a sweep over kilobytes of pairs.)
    s.narrow.wakes.resize(s.narrow.list.size());
    s.workers.for_ranges(int(s.narrow.list.size()), kConstraintGrain, [&](int begin, int end) {
      for (int k = begin; k < end; ++k) {
        if (k + kPrefetchAhead < end) prefetch_pair(s.list.pairs[s.narrow.list[k + kPrefetchAhead]]);
        Pair<N>& p = s.list.pairs[s.narrow.list[k]];
        collide_pair(s, p, bodies, shapes, settings, h);
        s.narrow.wakes[k] = p.manifold.count > 0 && (sleeps(p.a) || sleeps(p.b));
      }
    });
    for (std::size_t k = 0; k < s.narrow.list.size(); ++k) {
      if (!s.narrow.wakes[k]) continue;
      const Pair<N>& p = s.list.pairs[s.narrow.list[k]];
      for (const std::uint32_t i : {p.a, p.b})
        if (sleeps(i)) {  // (unless a pair before it woke it)
          s.islands.wake_island(int(i));
          again = true;
        }
    }
  }
}

#define WEDGE_INSTANTIATE(N)                                                                              \
  template void collide_pairs<N>(ContactState<N>&, const std::vector<Body<N>>&, const Shapes<N>&, \
                                 const ContactSettings&, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
