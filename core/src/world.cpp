// World step, body construction and diagnostics; explicitly instantiated for N = 2..6.
#include "wedge/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "contact/contact_system.hpp"
#include "dynamics/integrate.hpp"
#include "linalg/decompositions.hpp"
#include "linalg/fixed_size.hpp"
#include "wedge/error.hpp"
#include "wedge/fp_env.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {

template <int N>
Body<N> make_body(const BodyDef<N>& def) {
  const std::string who = def.name.empty() ? std::string("body") : "body '" + def.name + "'";
  if (!all_finite(def.position) || !all_finite(def.velocity) || !def.rotor.all_finite() ||
      !def.angular_velocity.all_finite())
    throw Error(who + ": position, rotor and velocities must be finite");
  const Rotor<N> rr = def.rotor * reverse(def.rotor);
  if ((rr - Rotor<N>::identity()).norm() > 1e-6)
    throw Error(who + ": rotor is not a rotation (R ~R differs from 1 by " +
                std::to_string((rr - Rotor<N>::identity()).norm()) + ")");
  // (Each value is classified before it is compared: an ordered comparison with NaN raises the invalid-
  // operation exception, which traps where traps are on.)
  if (!(std::isfinite(def.linear_drag) && def.linear_drag >= 0.0) ||
      !(std::isfinite(def.angular_drag) && def.angular_drag >= 0.0))
    throw Error(who + ": drag coefficients must be finite and >= 0");
  Body<N> b;
  b.type = def.type;
  b.rotor = repair(def.rotor);
  b.local_center = def.local_center;
  b.center = def.position + rotate(b.rotor, def.local_center);
  b.linear_drag = def.linear_drag;
  b.angular_drag = def.angular_drag;
  if (def.type == BodyType::Static) return b;  // never moves: velocities stay zero
  b.velocity = def.velocity;
  b.angular_velocity = def.angular_velocity;
  if (def.type == BodyType::Kinematic) return b;
  // 1 / 1e-320 overflows: refused just below. (volatile: the division must happen inside the guarded scope;
  // the compiler would otherwise be free to move it past the restored environment.)
  volatile double inv_mass = 0.0;
  {
    const ExpectedFpExceptions quiet;
    inv_mass = 1.0 / def.mass;
  }
  if (!(std::isfinite(def.mass) && def.mass > 0.0) || !std::isfinite(inv_mass)) {
    std::ostringstream s;  // (std::to_string would print 1e-320 as 0.000000)
    s << who << ": mass must be positive and finite, with a finite inverse (got " << def.mass << ")";
    throw Error(s.str());
  }
  if (!all_finite(def.inertia) || (def.inertia - def.inertia.transpose()).norm() > 1e-9 * def.inertia.norm())
    throw Error(who + ": inertia must be a finite symmetric matrix");
  const Eigen::VectorXd eig = linalg::symmetric_eigenvalues(def.inertia);
  if (!(eig[0] > 1e-12 * eig[kBiv<N> - 1]))
    throw Error(who + ": inertia must be positive definite");
  b.mass = def.mass;
  b.inv_mass = inv_mass;
  b.inertia = 0.5 * (def.inertia + def.inertia.transpose());
  {
    const ExpectedFpExceptions quiet;  // an inverse too large for a double is refused just below
    b.inv_inertia = linalg::inverse<kBiv<N>>(b.inertia);
  }
  if (!all_finite(b.inv_inertia)) throw Error(who + ": inertia is too small to invert (its inverse overflows)");
  b.inv_inertia = 0.5 * (b.inv_inertia + b.inv_inertia.transpose()).eval();
  return b;
}

namespace {
void check_contact_settings(const ContactSettings& c) {
  auto finite_nonneg = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!finite_nonneg(c.contact_margin)) throw Error("contact.contact_margin must be finite and >= 0 (m)");
  if (!finite_nonneg(c.continuous_gap)) throw Error("contact.continuous_gap must be finite and >= 0 (m)");
  if (!(finite_nonneg(c.max_turn) && c.max_turn > 0.0)) throw Error("contact.max_turn must be finite and > 0 (rad per step)");
  if (c.collision_iterations < 0 || c.contact_iterations < 0 || c.shock_iterations < 0 || c.position_iterations < 0)
    throw Error("contact iteration counts must be >= 0");
  if (c.substeps < 1 || c.substeps > 64) throw Error("contact.substeps must be in 1..64");
  if (!finite_nonneg(c.contact_hertz) || !finite_nonneg(c.contact_damping_ratio) || !finite_nonneg(c.contact_push_speed))
    throw Error("contact.contact_hertz (Hz), contact_damping_ratio and contact_push_speed (m/s) must be finite and >= 0");
  if (!finite_nonneg(c.joint_hertz) || !finite_nonneg(c.joint_damping_ratio) || !finite_nonneg(c.joint_angular_hertz))
    throw Error("contact.joint_hertz, joint_angular_hertz (Hz) and joint_damping_ratio must be finite and >= 0");
  if (!finite_nonneg(c.restitution_threshold)) throw Error("contact.restitution_threshold must be finite and >= 0 (m/s)");
  if (!finite_nonneg(c.recycle_distance) || !finite_nonneg(c.recycle_angle))
    throw Error("contact.recycle_distance (m) and recycle_angle (rad) must be finite and >= 0");
  if (!finite_nonneg(c.face_preference)) throw Error("contact.face_preference must be finite and >= 0 (m)");
  if (!finite_nonneg(c.static_slip_speed)) throw Error("contact.static_slip_speed must be finite and >= 0 (m/s)");
  if (!finite_nonneg(c.contact_tolerance)) throw Error("contact.contact_tolerance must be finite and >= 0 (m/s)");
  if (!finite_nonneg(c.shock_tolerance)) throw Error("contact.shock_tolerance must be finite and >= 0 (m/s)");
  if (!finite_nonneg(c.linear_slop)) throw Error("contact.linear_slop must be finite and >= 0 (m)");
  if (!(c.position_correction > 0.0 && c.position_correction <= 1.0))
    throw Error("contact.position_correction must be in (0, 1]");
  if (!finite_nonneg(c.sleep_linear_speed) || !finite_nonneg(c.time_to_sleep))
    throw Error("contact.sleep_linear_speed and time_to_sleep must be finite and >= 0");
}

void check_material(const Material& m, const std::string& who) {
  if (!(m.restitution >= 0.0 && m.restitution <= 1.0))
    throw Error(who + ": restitution must be in [0, 1] (got " + std::to_string(m.restitution) + ")");
  if (!(m.friction >= 0.0) || !std::isfinite(m.friction) || !(m.kinetic_friction >= 0.0) ||
      !std::isfinite(m.kinetic_friction))
    throw Error(who + ": friction coefficients must be finite and >= 0");
}

template <int N>
void check_world_settings(const WorldSettings<N>& s) {
  if (!all_finite(s.gravity)) throw Error("gravity must be finite");
  if (s.rotor_repair_interval < 1) throw Error("rotor_repair_interval must be >= 1");
  if (s.workers < 1 || s.workers > parallel::Workers::kMax)
    throw Error("workers must be in 1.." + std::to_string(parallel::Workers::kMax) + " (got " +
                std::to_string(s.workers) + ")");
  check_contact_settings(s.contact);
}
}  // namespace

template <int N>
World<N>::World(const WorldSettings<N>& settings)
    : settings_(settings), contact_(std::make_unique<contact::ContactState<N>>()) {
  check_world_settings(settings_);
  contact_->workers.resize(settings_.workers);
}

template <int N>
void World<N>::set_settings(const WorldSettings<N>& settings) {
  check_world_settings(settings);
  if (settings.contact.solver == ContactSolver::Paper && joint_count() > 0)
    throw Error("contact.solver: the paper's contact solver has no joints, and this world has " +
                std::to_string(joint_count()));
  set_gravity(settings.gravity);
  settings_ = settings;
  contact_->workers.resize(settings_.workers);
}

template <int N>
World<N>::~World() = default;
template <int N>
World<N>::World(World&&) noexcept = default;
template <int N>
World<N>& World<N>::operator=(World&&) noexcept = default;
template <int N>
World<N>::World(const World& o)
    : settings_(o.settings_),
      bodies_(o.bodies_),
      names_(o.names_),
      shapes_(o.shapes_),
      materials_(o.materials_),
      user_data_(o.user_data_),
      contact_(std::make_unique<contact::ContactState<N>>(*o.contact_)),
      steps_(o.steps_),
      profile_(o.profile_),
      time_(o.time_),
      time_error_(o.time_error_) {}
template <int N>
World<N>& World<N>::operator=(const World& o) {
  if (this != &o) *this = World(o);
  return *this;
}

template <int N>
BodyId World<N>::add_body(const BodyDef<N>& def) {
  const std::string who = def.name.empty() ? std::string("body") : "body '" + def.name + "'";
  if (def.shape && !def.shape->bounded() && def.type != BodyType::Static)
    throw Error(who + ": a half-space can only be the shape of a static body");
  check_material(def.material, who);
  bodies_.push_back(make_body(def));
  names_.push_back(def.name);
  shapes_.push_back(def.shape);
  materials_.push_back(def.material);
  user_data_.push_back(def.user_data);
  contact::add_body(*contact_, bodies_, shapes_, int(bodies_.size() - 1));
  return BodyId{std::uint32_t(bodies_.size() - 1)};
}

template <int N>
bool World<N>::is_awake(BodyId id) const {
  return contact_->islands.awake[check(id)] != 0;
}
template <int N>
void World<N>::wake(BodyId id) {
  contact_->islands.wake_island(int(check(id)));
}

template <int N>
void World<N>::move_kinematic(BodyId id, const Vec<N>& position, const Rotor<N>& rotor, double h) {
  Body<N>& b = bodies_[check(id)];
  if (b.type != BodyType::Kinematic) throw Error("move_kinematic: body '" + names_[id.index] + "' is not kinematic");
  if (!(h > 0.0) || !all_finite(position) || !rotor.all_finite()) throw Error("move_kinematic: invalid target");
  const Rotor<N> target = repair(rotor);
  // R' = exp(-h w / 2) R  =>  w = -2 log(R' ~R) / h; the centre follows the body frame.
  b.angular_velocity = log<N>(target * reverse(b.rotor)) * (-2.0 / h);
  b.velocity = (position + rotate(target, b.local_center) - b.center) / h;
}

template <int N>
std::uint32_t World<N>::check(BodyId id) const {
  if (id.index >= bodies_.size())
    throw Error("body id " + std::to_string(id.index) + " is not a body of this world (it has " +
                std::to_string(bodies_.size()) + ")");
  return id.index;
}

template <int N>
void World<N>::set_gravity(const Vec<N>& g) {
  if (!all_finite(g)) throw Error("set_gravity: gravity must be finite");
  if (g == settings_.gravity) return;
  settings_.gravity = g;
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].is_dynamic() && !contact_->islands.awake[i]) contact_->islands.wake(int(i));
}

template <int N>
std::uint32_t World<N>::check(GrabId id) const {
  const auto& grabs = contact_->grabs;
  if (id.index >= grabs.size() || !grabs[id.index].live || grabs[id.index].generation != id.generation)
    throw Error("grab id " + std::to_string(id.index) + "/" + std::to_string(id.generation) +
                " is not a live grab of this world");
  return id.index;
}

namespace {
template <int N>
void check_grab_target(const Vec<N>& target, const Vec<N>& velocity) {
  if (!all_finite(target) || !all_finite(velocity)) throw Error("grab: target and its velocity must be finite");
}
}  // namespace

template <int N>
GrabId World<N>::add_grab(const GrabDef<N>& def) {
  const Body<N>& b = bodies_[check(def.body)];
  if (!b.is_dynamic()) throw Error("add_grab: body '" + names_[def.body.index] + "' is not dynamic");
  if (!all_finite(def.local_point)) throw Error("add_grab: the grab point must be finite");
  check_grab_target(def.target, def.target_velocity);
  if (!(def.frequency > 0.0) || !std::isfinite(def.frequency)) throw Error("add_grab: frequency must be > 0 (Hz)");
  if (!(def.damping_ratio >= 0.0) || !std::isfinite(def.damping_ratio))
    throw Error("add_grab: damping_ratio must be finite and >= 0");
  if (!(def.max_acceleration > 0.0) || !std::isfinite(def.max_acceleration))
    throw Error("add_grab: max_acceleration must be finite and > 0 (m/s^2)");
  auto& grabs = contact_->grabs;
  std::size_t slot = 0;
  while (slot < grabs.size() && grabs[slot].live) ++slot;  // lowest free slot: a fixed, replayable order
  if (slot == grabs.size()) grabs.emplace_back();
  contact::GrabConstraint<N>& g = grabs[slot];
  const std::uint32_t generation = g.generation + 1;
  g = contact::GrabConstraint<N>{};
  g.def = def;
  g.generation = generation;
  g.live = true;
  contact_->islands.wake_island(int(def.body.index));
  return GrabId{std::uint32_t(slot), generation};
}

template <int N>
void World<N>::set_grab_target(GrabId id, const Vec<N>& target, const Vec<N>& velocity) {
  contact::GrabConstraint<N>& g = contact_->grabs[check(id)];
  check_grab_target(target, velocity);
  g.def.target = target;
  g.def.target_velocity = velocity;
  contact_->islands.wake_island(int(g.def.body.index));
}

template <int N>
void World<N>::remove_grab(GrabId id) {
  contact::GrabConstraint<N>& g = contact_->grabs[check(id)];
  g.live = false;
  g.active = false;
  g.impulse.setZero();
}

template <int N>
bool World<N>::has_grab(GrabId id) const {
  const auto& grabs = contact_->grabs;
  return id.index < grabs.size() && grabs[id.index].live && grabs[id.index].generation == id.generation;
}

template <int N>
const GrabDef<N>& World<N>::grab(GrabId id) const {
  return contact_->grabs[check(id)].def;
}

template <int N>
Vec<N> World<N>::grab_point(GrabId id) const {
  const GrabDef<N>& d = contact_->grabs[check(id)].def;
  const Body<N>& b = bodies_[d.body.index];
  return b.center + rotate(b.rotor, Vec<N>(d.local_point - b.local_center));
}

template <int N>
const std::vector<ContactBeginEvent<N>>& World<N>::contact_begin_events() const {
  return contact_->events.begin;
}
template <int N>
const std::vector<ContactEndEvent>& World<N>::contact_end_events() const {
  return contact_->events.end;
}
template <int N>
std::vector<ContactInfo<N>> World<N>::contacts() const {
  std::vector<ContactInfo<N>> out;
  for (const contact::Pair<N>& p : contact_->list.pairs) {
    if (p.manifold.count == 0) continue;
    ContactInfo<N> info;
    info.a = BodyId{p.a};
    info.b = BodyId{p.b};
    info.manifold = p.manifold;
    info.normal_impulse = p.normal_impulse;
    info.touching = p.touching;
    out.push_back(info);
  }
  return out;
}

template <int N>
void World<N>::apply_force(BodyId id, const Vec<N>& f) {
  check(id);
  if (!(all_finite(f))) throw Error("apply_force: non-finite input for body '" + names_[id.index] + "'");
  if (bodies_[id.index].is_dynamic()) contact_->islands.wake_island(int(id.index));
  bodies_[id.index].force += f;
}
template <int N>
void World<N>::apply_force_at(BodyId id, const Vec<N>& f, const Vec<N>& p) {
  check(id);
  if (!(all_finite(f) && all_finite(p))) throw Error("apply_force_at: non-finite input for body '" + names_[id.index] + "'");
  if (bodies_[id.index].is_dynamic()) contact_->islands.wake_island(int(id.index));
  Body<N>& b = bodies_[id.index];
  b.force += f;
  b.torque += outer<N>(p - b.center, f);
}
template <int N>
void World<N>::apply_torque(BodyId id, const Bivector<N>& t) {
  check(id);
  if (!(t.all_finite())) throw Error("apply_torque: non-finite input for body '" + names_[id.index] + "'");
  if (bodies_[id.index].is_dynamic()) contact_->islands.wake_island(int(id.index));
  bodies_[id.index].torque += t;
}
template <int N>
void World<N>::apply_impulse_at(BodyId id, const Vec<N>& j, const Vec<N>& p) {
  check(id);
  if (!(all_finite(j) && all_finite(p))) throw Error("apply_impulse_at: non-finite input for body '" + names_[id.index] + "'");
  if (bodies_[id.index].is_dynamic()) contact_->islands.wake_island(int(id.index));
  Body<N>& b = bodies_[id.index];
  if (!b.is_dynamic()) return;
  b.velocity += j * b.inv_mass;
  b.angular_velocity.c += b.world_inv_inertia() * (wedge_matrix<N>(p - b.center) * j);
}
template <int N>
void World<N>::apply_angular_impulse(BodyId id, const Bivector<N>& j) {
  check(id);
  if (!(j.all_finite())) throw Error("apply_angular_impulse: non-finite input for body '" + names_[id.index] + "'");
  if (bodies_[id.index].is_dynamic()) contact_->islands.wake_island(int(id.index));
  Body<N>& b = bodies_[id.index];
  if (!b.is_dynamic()) return;
  b.angular_velocity.c += b.world_inv_inertia() * j.c;
}

template <int N>
void World<N>::step(double h) {
  StageClock total;
  profile_ = StepProfile{};
  contact_->workers.resize(settings_.workers);
  find_contacts(h);  // (find_contacts and soft_step time their own stages)
  if (settings_.contact.solver == ContactSolver::SoftStep) {
    soft_step(h);
  } else {
    StageClock solver;
    process_collisions(h);
    integrate_velocities(h);
    process_contacts(h);
    profile_.solve = solver.lap();
    integrate_positions(h);
    profile_.integrate_positions = solver.lap();
  }
  StageClock clock;
  contact::solve_continuous(*contact_, bodies_, shapes_, materials_, settings_.contact, h);
  profile_.continuous = clock.lap();
  update_islands(h);
  profile_.islands = clock.lap();
  report_contact_events();
  profile_.events = clock.lap();
  clear_forces();
  ++steps_;
  // Neumaier's compensated sum: 600 steps of 1/120 s come to 5 s exactly, not 4.99999999999998.
  const double t = time_ + h;
  time_error_ += std::abs(time_) >= h ? (time_ - t) + h : (h - t) + time_;
  time_ = t;
  profile_.step = total.lap();
}

template <int N>
void World<N>::find_contacts(double h) {
  contact::find_contacts(*contact_, bodies_, shapes_, materials_, settings_.contact, h, &profile_);
}
// The soft step's stages (contact/soft_step.cpp): its velocities live in the solver bodies through its
// sub-steps, which integrate them and move the bodies.
template <int N>
void World<N>::soft_step(double h) {
  const ContactSettings& c = settings_.contact;
  const double hs = h / c.substeps;
  const dynamics::Motion<N> motion = dynamics::motion_of(settings_);
  const bool repair_at_end = (steps_ + 1) % settings_.rotor_repair_interval == 0;
  StageClock clock;
  contact::prepare_soft_step(*contact_, bodies_, c, hs, &motion);
  for (int i = 0; i < c.substeps; ++i) {
    contact::integrate_velocities_apart(*contact_, bodies_, motion, hs);
    contact::solve_substep(*contact_, bodies_, c, hs, true);  // (the others' velocities first)
    profile_.solve += clock.lap();
    contact::integrate_substep_positions(*contact_, bodies_, hs, repair_at_end && i == c.substeps - 1);
    profile_.integrate_positions += clock.lap();
    contact::solve_substep(*contact_, bodies_, c, hs, false);
    profile_.relax += clock.lap();
  }
  contact::integrate_alone(*contact_, bodies_, motion, hs, c.substeps, repair_at_end);
  profile_.integrate_positions += clock.lap();
  contact::finish_soft_step(*contact_, bodies_, c);
  profile_.finish = clock.lap();
}

template <int N>
void World<N>::process_collisions(double h) {
  contact::process_collisions(*contact_, bodies_, settings_.contact, h);
}
template <int N>
void World<N>::process_contacts(double h) {
  contact::process_contacts(*contact_, bodies_, settings_.contact, h);
}
template <int N>
void World<N>::update_islands(double h) {
  contact::update_islands(*contact_, bodies_, settings_.contact, h);
}
template <int N>
void World<N>::report_contact_events() {
  contact::report_events(*contact_);
}

// Symplectic Euler, velocity half (dynamics::integrate_velocity).
template <int N>
void World<N>::integrate_velocities(double h) {
  const dynamics::Motion<N> motion = dynamics::motion_of(settings_);
  contact::for_each_body(*contact_, int(bodies_.size()), [&](int i) {
    Body<N>& b = bodies_[i];
    if (!b.is_dynamic() || !contact_->islands.awake[i]) return;
    dynamics::integrate_velocity(b, motion, h, b.velocity, b.angular_velocity);
  });
}

// Position half: the paper's solver moves the bodies with their velocities and its pseudo velocities
// (contact::integrate_positions).
template <int N>
void World<N>::integrate_positions(double h) {
  const bool repair_now = (steps_ + 1) % settings_.rotor_repair_interval == 0;
  contact::integrate_positions(*contact_, bodies_, h, repair_now);
}

template <int N>
void World<N>::clear_forces() {
  for (Body<N>& b : bodies_) {
    b.force.setZero();
    b.torque = Bivector<N>{};
  }
}

template <int N>
double World<N>::kinetic_energy() const {
  double e = 0.0;
  for (const Body<N>& b : bodies_) e += b.kinetic_energy();
  return e;
}
template <int N>
double World<N>::potential_energy() const {
  double e = 0.0;
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) e -= b.mass * settings_.gravity.dot(b.center);
  return e;
}
template <int N>
Vec<N> World<N>::linear_momentum() const {
  Vec<N> p = Vec<N>::Zero();
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) p += b.mass * b.velocity;
  return p;
}
template <int N>
Bivector<N> World<N>::angular_momentum() const {
  Bivector<N> l;
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) l += outer<N>(b.center, b.mass * b.velocity) + b.angular_momentum();
  return l;
}

template <int N>
std::uint64_t World<N>::state_hash() const {
  std::uint64_t hash = 14695981039346656037ull;
  auto mix = [&hash](const double* data, int count) {
    unsigned char bytes[sizeof(double)];
    for (int i = 0; i < count; ++i) {
      const double v = data[i] == 0.0 ? 0.0 : data[i];  // -0 and +0 hash alike
      std::memcpy(bytes, &v, sizeof v);
      for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
    }
  };
  for (const Body<N>& b : bodies_) {
    mix(b.center.data(), N);
    mix(b.rotor.c.data(), kEven<N>);
    mix(b.velocity.data(), N);
    mix(b.angular_velocity.c.data(), kBiv<N>);
  }
  return hash;
}

#define WEDGE_INSTANTIATE(N)                                                                    \
  template Body<N> make_body<N>(const BodyDef<N>&);                                            \
  template class World<N>;
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
