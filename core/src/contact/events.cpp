// The contact events: which pairs began or stopped touching in this step.
#include <algorithm>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

// A pair is touching when some point received a normal impulse or penetrates; pairs not collided in
// this step (asleep) keep their state.
template <int N>
void report_events(ContactState<N>& s) {
  s.events.begin.clear();
  s.events.end = s.events.ended;
  for (Pair<N>& p : s.list.pairs) {
    if (!p.updated) continue;
    // A penetrating pair touches whatever its impulses: those are read only where they decide, or
    // for a begin event (most resting pairs penetrate a little, and need not read them).
    const bool penetrating = p.manifold.count > 0 && p.manifold.depth > 0.0;
    if (p.constraint < 0) p.normal_impulse.fill(0.0);
    if (penetrating && p.touching) continue;  // (touching, and it was: no event)
    double total = 0.0;  // (its points' totals are in normal_impulse: unpack_wide, keep_totals)
    if (p.constraint >= 0)
      for (int k = 0; k < p.manifold.count; ++k) total += p.normal_impulse[k];
    const bool touching = total > 0.0 || penetrating;
    if (touching && !p.touching) {
      Vec<N> weighted = Vec<N>::Zero();
      if (p.constraint >= 0)
        for (int k = 0; k < p.manifold.count; ++k) weighted += p.normal_impulse[k] * p.manifold.points[k].point;
      const double approach = p.constraint >= 0 ? p.approach_speed : 0.0;
      ContactBeginEvent<N> e;
      e.a = BodyId{p.a};
      e.b = BodyId{p.b};
      e.normal = p.manifold.normal;
      e.normal_impulse = total;
      e.point = total > 0.0 ? Vec<N>(weighted / total) : p.manifold.points[0].point;
      e.approach_speed = approach;
      s.events.begin.push_back(e);
    } else if (!touching && p.touching) {
      s.events.end.push_back({BodyId{p.a}, BodyId{p.b}});
    }
    p.touching = touching;
  }
  std::sort(s.events.end.begin(), s.events.end.end(), [](const ContactEndEvent& x, const ContactEndEvent& y) {
    return x.a.index != y.a.index ? x.a.index < y.a.index : x.b.index < y.b.index;
  });
}

#define WEDGE_INSTANTIATE(N) template void report_events<N>(ContactState<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
