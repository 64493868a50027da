// The constraint graph: which pairs make a constraint this step (the seeds), and, unless they are the
// last step's, where each constraint goes: in pair order for the paper's solver, in colour order for
// the soft step, whose lanes are then assigned (soft_step.cpp, assign_lanes).
#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <type_traits>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

namespace {

// Graph colouring (Box2D v3's constraint graph): each constraint takes the lowest colour that neither of
// its moving bodies has yet, and the constraints are solved colour by colour, in pair order within a
// colour. No two constraints of a colour share a moving body, so consecutive ones are independent and
// the processor overlaps them instead of waiting on one body's velocities. Static and sleeping bodies
// are only read and take no colour. A body in more than kColours constraints sends the rest to a last,
// uncoloured group. Deterministic: a function of the pair order alone.
template <int N>
void colour_constraints(ContactState<N>& s, std::size_t bodies) {
  constexpr int kColours = 32;  // the bits of a body's mask: countr_one gives kColours when all are taken
  static_assert(kColours == std::numeric_limits<std::uint32_t>::digits);
  s.graph.colour_mask.assign(bodies, 0);
  s.graph.colour_of.resize(s.graph.seeds.size());
  std::array<int, kColours + 3> start{};
  for (std::size_t k = 0; k < s.graph.seeds.size(); ++k) {
    const auto& e = s.graph.seeds[k];
    const std::uint32_t used = (e.move_a ? s.graph.colour_mask[e.a] : 0u) | (e.move_b ? s.graph.colour_mask[e.b] : 0u);
    const int c = std::countr_one(used);
    if (c < kColours) {
      if (e.move_a) s.graph.colour_mask[e.a] |= 1u << c;
      if (e.move_b) s.graph.colour_mask[e.b] |= 1u << c;
    }
    s.graph.colour_of[k] = c;
    ++start[c + 2];
  }
  for (int c = 2; c < kColours + 3; ++c) start[c] += start[c - 1];  // start[c + 1]: where colour c begins
  s.graph.colour_start.assign(start.begin() + 1, start.end());
  s.graph.colour_order.resize(s.graph.seeds.size());  // (of the seeds)
  for (std::size_t k = 0; k < s.graph.seeds.size(); ++k) s.graph.colour_order[start[s.graph.colour_of[k] + 1]++] = int(k);
}

// Where each constraint's points go (and its bodies and count, which the lanes are assigned by), in
// colour order (soft step) or pair order, from the seeds, and for the soft step the lanes. (Not
// cleared first: the build writes each constraint whole, and value-initialising them all was a tenth
// of the build's time.)
template <int N>
void place_constraints(ContactState<N>& s, std::size_t bodies, bool soft) {
  s.graph.colour_start.clear();
  if (soft) colour_constraints(s, bodies);
  const std::size_t count = s.graph.seeds.size();
  s.graph.constraints.resize(count);
  s.graph.constraint_pairs.resize(count);
  int total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const auto& e = s.graph.seeds[soft ? std::size_t(s.graph.colour_order[k]) : k];
    s.graph.constraint_pairs[k] = e.pair;
    Constraint<N>& c = s.graph.constraints[k];
    c.first = total;
    c.count = e.count;
    c.a = int(e.a);
    c.b = int(e.b);
    total += c.count;
  }
  if (soft) assign_lanes(s);
}

}  // namespace

template <int N>
void update_constraint_graph(ContactState<N>& s, const std::vector<Body<N>>& bodies, bool soft) {
  s.graph.seeds.swap(s.graph.previous_seeds);
  s.graph.seeds.clear();
  for (std::size_t pi = 0; pi < s.list.pairs.size(); ++pi) {
    Pair<N>& p = s.list.pairs[pi];
    p.constraint = -1;
    if (!p.updated) continue;
    if (p.manifold.count == 0) {
      p.warm_count = 0;
      continue;
    }
    const bool da = moves(s, bodies, p.a), db = moves(s, bodies, p.b);
    if (!da && !db) continue;
    s.graph.seeds.push_back({int(pi), p.a, p.b, p.manifold.count, da, db, !da || s.masses[p.a].isotropic,
                       !db || s.masses[p.b].isotropic});
  }
  // The same seeds as the last soft step's: the same colours and lanes, and the constraints' places.
  static_assert(std::has_unique_object_representations_v<typename ConstraintGraph<N>::Seed>);  // (memcmp is ==)
  s.graph.graph_kept = soft && s.graph.built_soft && s.graph.seeds.size() == s.graph.previous_seeds.size() &&
                 (s.graph.seeds.empty() ||
                  std::memcmp(s.graph.seeds.data(), s.graph.previous_seeds.data(), s.graph.seeds.size() * sizeof(s.graph.seeds[0])) == 0);
  if (!s.graph.graph_kept) place_constraints(s, bodies.size(), soft);
}

#define WEDGE_INSTANTIATE(N) \
  template void update_constraint_graph<N>(ContactState<N>&, const std::vector<Body<N>>&, bool);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
