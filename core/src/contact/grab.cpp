// Grabs as soft point constraints, solved in process_contacts before the contacts of every pass (see
// wedge/grab.hpp for the spring and its coefficients).
#include <cmath>

#include "contact/contact_system.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/softness.hpp"

namespace wedge::contact {

template <int N>
bool prepare_grabs(ContactState<N>& s, const std::vector<Body<N>>& bodies, double h) {
  if (s.grabs.empty()) {  // (the usual world: nothing per body to clear each step)
    s.driven.clear();
    return false;
  }
  s.driven.assign(bodies.size(), 0);
  bool any = false;
  for (GrabConstraint<N>& g : s.grabs) {
    const std::uint32_t i = g.def.body.index;
    g.active = g.live && moves(s, bodies, i);
    if (!g.active) continue;
    const Body<N>& b = bodies[i];
    const BodyMass<N>& sb = s.masses[i];
    g.inv_mass = sb.inv_mass;
    g.r = rotate(b.rotor, Vec<N>(g.def.local_point - b.local_center));
    const WedgeMat<N> jr = wedge_matrix<N>(g.r);
    g.w = sb.inv_inertia * jr;
    const Mat<N> k = sb.inv_mass * Mat<N>::Identity() + jr.transpose() * g.w;
    g.mass = linalg::inverse<N>(k);
    const Softness soft = make_softness(g.def.frequency, g.def.damping_ratio, h);
    g.mass_scale = soft.mass_scale;
    g.impulse_scale = soft.impulse_scale;
    g.bias = soft.bias_rate * (b.center + g.r - g.def.target);
    g.max_impulse = b.mass * g.def.max_acceleration * h;
    if (!all_finite(g.mass)) {  // (K is positive definite for a valid body; never let a NaN in)
      g.active = false;
      continue;
    }
    s.driven[i] = 1;
    any = true;
  }
  return any;
}

template <int N>
void warm_start_grabs(ContactState<N>& s) {
  for (GrabConstraint<N>& g : s.grabs) {
    if (!g.active) continue;
    SolverBody<N>& b = s.solver_bodies[g.def.body.index];
    b.v += g.inv_mass * g.impulse;
    b.w.c += g.w * g.impulse;
  }
}

template <int N>
double solve_grabs(ContactState<N>& s) {
  double largest = 0.0;
  for (GrabConstraint<N>& g : s.grabs) {
    if (!g.active) continue;
    SolverBody<N>& b = s.solver_bodies[g.def.body.index];
    const Vec<N> cdot = b.v + dot<N>(g.r, b.w) - g.def.target_velocity;
    const Vec<N> old = g.impulse;
    g.impulse += -g.mass_scale * (g.mass * (cdot + g.bias)) - g.impulse_scale * old;
    const double norm = g.impulse.norm();
    if (norm > g.max_impulse) g.impulse *= g.max_impulse / norm;
    const Vec<N> j = g.impulse - old;
    b.v += g.inv_mass * j;
    b.w.c += g.w * j;
    largest = std::max(largest, j.norm() * g.inv_mass);
  }
  return largest;
}

#define WEDGE_INSTANTIATE(N)                                                                    \
  template bool prepare_grabs<N>(ContactState<N>&, const std::vector<Body<N>>&, double); \
  template void warm_start_grabs<N>(ContactState<N>&);                                    \
  template double solve_grabs<N>(ContactState<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
