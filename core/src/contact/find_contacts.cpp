// find_contacts, the contact stages World::step runs before its solver, as named stages: the pair list
// (pairs.cpp), the narrow phase (collide.cpp), the solver bodies and the constraints (build.cpp, whose
// graph is constraint_graph.cpp), and for the paper's solver the contact graph's levels (islands.cpp).
#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::contact {

template <int N>
void find_contacts(ContactState<N>& s, std::vector<Body<N>>& bodies, const Shapes<N>& shapes,
                   const std::vector<Material>& materials, const ContactSettings& settings, double h,
                   StepProfile* profile) {
  StageClock clock;
  update_pairs(s, bodies, shapes, h);
  const double broad = clock.lap();
  collide_pairs(s, bodies, shapes, settings, h);
  const double narrow = clock.lap();
  load_solver_bodies(s, bodies, settings.solver == ContactSolver::SoftStep);
  build_constraints(s, bodies, materials, settings);
  if (settings.solver == ContactSolver::Paper && settings.shock_iterations > 0) compute_levels(s, bodies);
  if (profile) {
    profile->broad_phase = broad;
    profile->narrow_phase = narrow;
    profile->constraints = clock.lap();
  }
}

#define WEDGE_INSTANTIATE(N)                                                                                  \
  template void find_contacts<N>(ContactState<N>&, std::vector<Body<N>>&, const Shapes<N>&,                   \
                                 const std::vector<Material>&, const ContactSettings&, double, StepProfile*);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::contact
