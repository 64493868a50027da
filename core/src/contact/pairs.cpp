// The persistent pair list: each body's broad-phase proxy and box, the candidate pairs (the broad
// phase's, and each half-space with the bodies near its plane), merged each step into the sorted list
// of pairs that carries each pair's manifold, warm start and touching state from step to step.
#include <algorithm>

#include "contact/contact_system.hpp"
#include "collision/shape_extent.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

// Moves the proxies of the bodies that can move, then lists the candidate pairs: the broad phase's,
// plus each half-space with every dynamic body whose box reaches within the margin of its plane. Where
// neither changed (a resting scene) the list is left as it is.
template <int N>
void update_broad_phase(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, double h) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body<N>& b = bodies[i];
    if (s.list.proxy[i] < 0 || b.type == BodyType::Static || !s.islands.awake[i]) continue;
    s.list.box[i] = world_aabb(*shapes[i], b.position(), b.rotor);
    s.list.broad_phase.move_proxy(s.list.proxy[i], s.list.box[i], Vec<N>(b.velocity * h));
  }
  const bool tree_changed = s.list.broad_phase.update_pairs();
  // The half-space pairs, sorted. (The box is read first: most bodies are far from every plane, and
  // their type need not be read.)
  s.list.halfspace_pairs.swap(s.list.previous_halfspace_pairs);
  s.list.halfspace_pairs.clear();
  const double margin = s.list.broad_phase.settings().margin;
  for (const std::uint32_t hs : s.list.halfspaces) {
    const Body<N>& g = bodies[hs];
    const auto& plane = shapes[hs]->template as<shapes::Halfspace<N>>();
    const Vec<N> n = rotate(g.rotor, plane.normal);
    const double offset = plane.offset + n.dot(g.position());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (s.list.proxy[i] < 0) continue;
      const Aabb<N>& box = s.list.box[i];
      double low = 0.0;  // the box's lowest point along n
      for (int k = 0; k < N; ++k) low += n[k] * (n[k] > 0.0 ? box.lo[k] : box.hi[k]);
      if (low <= offset + margin && bodies[i].is_dynamic())
        s.list.halfspace_pairs.emplace_back(std::min<std::uint32_t>(hs, std::uint32_t(i)),
                                       std::max<std::uint32_t>(hs, std::uint32_t(i)));
    }
  }
  std::sort(s.list.halfspace_pairs.begin(), s.list.halfspace_pairs.end());
  if (!tree_changed && s.list.halfspace_pairs == s.list.previous_halfspace_pairs) return;
  // Merged into the broad phase's sorted list.
  const auto& tree = s.list.broad_phase.pairs();
  s.list.candidate_pairs.resize(tree.size() + s.list.halfspace_pairs.size());
  std::merge(tree.begin(), tree.end(), s.list.halfspace_pairs.begin(), s.list.halfspace_pairs.end(), s.list.candidate_pairs.begin());
}

// The new pair list, carrying each surviving pair's manifold and touching state over; a pair that
// leaves while touching ends.
template <int N>
void merge_pairs(ContactState<N>& s, const std::vector<Body<N>>& bodies) {
  s.events.ended.clear();
  // Usually (a resting heap) the list is unchanged: keep it rather than copy every pair (4D: kilobytes),
  // which the keys tell without reading the pairs.
  const auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t{a} << 32 | b; };
  // A pair of bodies that never collide: neither dynamic, or joined by a joint that says so.
  const std::vector<std::uint64_t>& joined = s.joints.no_collide;
  const auto skip = [&](std::uint32_t a, std::uint32_t b) {
    return (!bodies[a].is_dynamic() && !bodies[b].is_dynamic()) ||
           (!joined.empty() && std::binary_search(joined.begin(), joined.end(), key(a, b)));
  };
  const auto unchanged = [&] {
    std::size_t k = 0;
    for (const auto& [a, b] : s.list.candidate_pairs) {
      if (skip(a, b)) continue;
      if (k == s.list.pair_keys.size() || s.list.pair_keys[k] != key(a, b)) return false;
      ++k;
    }
    return k == s.list.pair_keys.size();
  };
  if (unchanged()) return;
  s.list.next_pairs.clear();
  std::size_t old = 0;
  auto drop = [&s](const Pair<N>& p) {
    if (p.touching) s.events.ended.push_back({BodyId{p.a}, BodyId{p.b}});
  };
  for (const auto& [a, b] : s.list.candidate_pairs) {
    if (skip(a, b)) continue;
    while (old < s.list.pairs.size() && (s.list.pairs[old].a < a || (s.list.pairs[old].a == a && s.list.pairs[old].b < b)))
      drop(s.list.pairs[old++]);
    if (old < s.list.pairs.size() && s.list.pairs[old].a == a && s.list.pairs[old].b == b) {
      s.list.next_pairs.push_back(s.list.pairs[old++]);
    } else {
      Pair<N> p;
      p.a = a;
      p.b = b;
      s.list.next_pairs.push_back(p);
    }
  }
  for (; old < s.list.pairs.size(); ++old) drop(s.list.pairs[old]);
  s.list.pairs.swap(s.list.next_pairs);
  s.list.pair_keys.resize(s.list.pairs.size());
  for (std::size_t k = 0; k < s.list.pairs.size(); ++k) s.list.pair_keys[k] = key(s.list.pairs[k].a, s.list.pairs[k].b);
}

}  // namespace

template <int N>
void add_body(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, int index) {
  s.islands.awake.push_back(1);
  s.islands.sleep_time.push_back(0.0);
  s.islands.island.push_back(-1);
  s.list.proxy.push_back(-1);
  s.list.box.push_back(Aabb<N>{});
  s.solver_bodies.emplace_back();
  s.masses.emplace_back();
  s.list.radius.push_back(0.0);
  s.list.inradius.push_back(0.0);
  const Shape<N>* shape = shapes[index].get();
  if (!shape) return;
  s.list.radius[index] = collision::shape_radius(*shape, bodies[index].local_center);
  s.list.inradius[index] = collision::shape_inradius(*shape, bodies[index].local_center);
  if (!shape->bounded()) {
    s.list.halfspaces.push_back(std::uint32_t(index));
    return;
  }
  s.list.box[index] = world_aabb(*shape, bodies[index].position(), bodies[index].rotor);
  s.list.proxy[index] = s.list.broad_phase.create_proxy(s.list.box[index], std::uint32_t(index));
}

template <int N>
void update_pairs(ContactState<N>& s, const std::vector<Body<N>>& bodies, const Shapes<N>& shapes, double h) {
  update_broad_phase(s, bodies, shapes, h);
  merge_pairs(s, bodies);
}

#define WEDGE_INSTANTIATE(N)                                                                        \
  template void add_body<N>(ContactState<N>&, const std::vector<Body<N>>&, const Shapes<N>&, int); \
  template void update_pairs<N>(ContactState<N>&, const std::vector<Body<N>>&, const Shapes<N>&, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
