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
  s.colour_mask.assign(bodies, 0);
  s.colour_of.resize(s.seeds.size());
  std::array<int, kColours + 3> start{};
  for (std::size_t k = 0; k < s.seeds.size(); ++k) {
    const auto& e = s.seeds[k];
    const std::uint32_t used = (e.move_a ? s.colour_mask[e.a] : 0u) | (e.move_b ? s.colour_mask[e.b] : 0u);
    const int c = std::countr_one(used);
    if (c < kColours) {
      if (e.move_a) s.colour_mask[e.a] |= 1u << c;
      if (e.move_b) s.colour_mask[e.b] |= 1u << c;
    }
    s.colour_of[k] = c;
    ++start[c + 2];
  }
  for (int c = 2; c < kColours + 3; ++c) start[c] += start[c - 1];  // start[c + 1]: where colour c begins
  s.colour_start.assign(start.begin() + 1, start.end());
  s.colour_order.resize(s.seeds.size());  // (of the seeds)
  for (std::size_t k = 0; k < s.seeds.size(); ++k) s.colour_order[start[s.colour_of[k] + 1]++] = int(k);
}

// Where each constraint's points go (and its bodies and count, which the lanes are assigned by), in
// colour order (soft step) or pair order, from the seeds, and for the soft step the lanes. (Not
// cleared first: the build writes each constraint whole, and value-initialising them all was a tenth
// of the build's time.)
template <int N>
void place_constraints(ContactState<N>& s, std::size_t bodies, bool soft) {
  s.colour_start.clear();
  if (soft) colour_constraints(s, bodies);
  const std::size_t count = s.seeds.size();
  s.constraints.resize(count);
  s.constraint_pairs.resize(count);
  int total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const auto& e = s.seeds[soft ? std::size_t(s.colour_order[k]) : k];
    s.constraint_pairs[k] = e.pair;
    Constraint<N>& c = s.constraints[k];
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
  s.seeds.swap(s.previous_seeds);
  s.seeds.clear();
  for (std::size_t pi = 0; pi < s.pairs.size(); ++pi) {
    Pair<N>& p = s.pairs[pi];
    p.constraint = -1;
    if (!p.updated) continue;
    if (p.manifold.count == 0) {
      p.warm_count = 0;
      continue;
    }
    const bool da = moves(s, bodies, p.a), db = moves(s, bodies, p.b);
    if (!da && !db) continue;
    s.seeds.push_back({int(pi), p.a, p.b, p.manifold.count, da, db, !da || s.solver_bodies[p.a].isotropic,
                       !db || s.solver_bodies[p.b].isotropic});
  }
  // The same seeds as the last soft step's: the same colours and lanes, and the constraints' places.
  static_assert(std::has_unique_object_representations_v<typename ContactState<N>::Seed>);  // (memcmp is ==)
  s.graph_kept = soft && s.built_soft && s.seeds.size() == s.previous_seeds.size() &&
                 (s.seeds.empty() ||
                  std::memcmp(s.seeds.data(), s.previous_seeds.data(), s.seeds.size() * sizeof(s.seeds[0])) == 0);
  if (!s.graph_kept) place_constraints(s, bodies.size(), soft);
}

#define WEDGE_INSTANTIATE(N) \
  template void update_constraint_graph<N>(ContactState<N>&, const std::vector<Body<N>>&, bool);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
