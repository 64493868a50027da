// World's joints (wedge/joint.hpp): each definition checked and turned into a slot of the joint solver
// (contact/joint.hpp, solved by contact/joints.cpp), removal, and the queries on a joint.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "contact/contact_system.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/error.hpp"
#include "wedge/world.hpp"

namespace wedge {

template <int N>
std::uint32_t World<N>::check(JointId id) const {
  const auto& slots = contact_->joints.slots;
  if (id.index >= slots.size() || !slots[id.index].live || slots[id.index].generation != id.generation)
    throw Error("joint id " + std::to_string(id.index) + "/" + std::to_string(id.generation) +
                " is not a live joint of this world");
  return id.index;
}

namespace {
std::uint64_t joined_key(int a, int b) {
  return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
}
}  // namespace

template <int N>
contact::JointConstraint<N> World<N>::joint_bodies(const JointBodies<N>& def, JointType type) const {
  if (settings_.contact.solver == ContactSolver::Paper)
    throw Error("add_joint: the paper's contact solver (contact.solver \"paper\") has no joints; use the soft step");
  const Body<N>& b = bodies_[check(def.body_b)];
  const bool a_dynamic = def.body_a && bodies_[check(*def.body_a)].is_dynamic();
  if (def.body_a && def.body_a->index == def.body_b.index)
    throw Error("add_joint: body_a and body_b are the same body '" + names_[def.body_b.index] + "'");
  if (!b.is_dynamic() && !a_dynamic)
    throw Error("add_joint: neither body is dynamic ('" + names_[def.body_b.index] + "'" +
                (def.body_a ? " and '" + names_[def.body_a->index] + "'" : std::string(" and the world")) + ")");
  if (!all_finite(def.anchor_a) || !all_finite(def.anchor_b)) throw Error("add_joint: the anchors must be finite");
  contact::JointConstraint<N> j;
  j.type = type;
  j.b = int(def.body_b.index);
  j.local_b = def.anchor_b - b.local_center;
  if (def.body_a) {
    j.a = int(def.body_a->index);
    j.local_a = def.anchor_a - bodies_[j.a].local_center;
  } else {
    j.local_a = def.anchor_a;
  }
  j.collide_connected = def.collide_connected;
  return j;
}

template <int N>
JointId World<N>::insert_joint(const contact::JointConstraint<N>& joint) {
  auto& js = contact_->joints;
  std::size_t slot = js.slots.size();
  if (js.free_slots.empty()) {
    js.slots.emplace_back();
  } else {  // the lowest free slot: a fixed, replayable order
    std::pop_heap(js.free_slots.begin(), js.free_slots.end(), std::greater<>{});
    slot = js.free_slots.back();
    js.free_slots.pop_back();
  }
  contact::JointConstraint<N>& j = js.slots[slot];
  const std::uint32_t generation = j.generation + 1;
  j = joint;
  j.generation = generation;
  j.live = true;
  if (j.a >= 0 && !j.collide_connected) {
    const std::uint64_t key = joined_key(j.a, j.b);
    js.no_collide.insert(std::upper_bound(js.no_collide.begin(), js.no_collide.end(), key), key);
  }
  if (j.a >= 0) contact_->islands.wake_island(j.a);
  contact_->islands.wake_island(j.b);
  return JointId{std::uint32_t(slot), generation};
}

template <int N>
JointId World<N>::add_joint(const PointJointDef<N>& def) {
  return insert_joint(joint_bodies(def, JointType::Point));
}

template <int N>
JointId World<N>::add_joint(const DistanceJointDef<N>& def) {
  contact::JointConstraint<N> j = joint_bodies(def, JointType::Distance);
  const auto finite_nonneg = [](double x) { return std::isfinite(x) && x >= 0.0; };
  const auto anchor_a = [&] { return def.body_a ? bodies_[j.a].center + rotate(bodies_[j.a].rotor, j.local_a) : j.local_a; };
  const Body<N>& b = bodies_[j.b];
  j.length = def.length;
  if (std::isfinite(def.length) && def.length < 0.0) j.length = (b.center + rotate(b.rotor, j.local_b) - anchor_a()).norm();
  if (!def.spring) {
    if (!(std::isfinite(j.length) && j.length >= 1e-4))
      throw Error("add_joint: a distance joint's length must be finite and >= 0.1 mm (got " + std::to_string(j.length) +
                  " m); anchors that meet are a point joint");
    return insert_joint(j);
  }
  if (!finite_nonneg(def.frequency)) throw Error("add_joint: frequency must be finite and >= 0 (Hz)");
  if (!finite_nonneg(def.damping_ratio)) throw Error("add_joint: damping_ratio must be finite and >= 0");
  if (!finite_nonneg(def.min_length)) throw Error("add_joint: min_length must be finite and >= 0 (m)");
  if (!(def.max_length >= def.min_length))
    throw Error("add_joint: max_length (" + std::to_string(def.max_length) + " m) must be >= min_length (" +
                std::to_string(def.min_length) + " m)");
  if (!(std::isfinite(j.length) && j.length >= def.min_length && j.length <= def.max_length))
    throw Error("add_joint: the spring's length (" + std::to_string(j.length) + " m) must lie in [min_length, max_length]");
  j.spring = true;
  j.frequency = def.frequency;
  j.damping_ratio = def.damping_ratio;
  j.min_length = def.min_length;
  j.max_length = def.max_length;
  return insert_joint(j);
}

template <int N>
Rotor<N> World<N>::joint_rotor_a(const contact::JointConstraint<N>& j) const {
  return j.a >= 0 ? bodies_[j.a].rotor : Rotor<N>::identity();
}

template <int N>
JointId World<N>::add_joint(const RevoluteJointDef<N>& def) {
  contact::JointConstraint<N> j = joint_bodies(def, JointType::Revolute);
  const auto orthonormal = [](const Vec<N>& u, const Vec<N>& v) {
    return all_finite(u) && all_finite(v) && std::abs(u.norm() - 1.0) < 1e-9 && std::abs(v.norm() - 1.0) < 1e-9 &&
           std::abs(u.dot(v)) < 1e-9;
  };
  if (!orthonormal(def.plane_u_a, def.plane_v_a))
    throw Error("add_joint: plane_u_a and plane_v_a must be orthonormal (unit length, at right angles, to 1e-9)");
  if (!orthonormal(def.plane_u_b, def.plane_v_b))
    throw Error("add_joint: plane_u_b and plane_v_b must be orthonormal (unit length, at right angles, to 1e-9)");
  const Rotor<N> ra = joint_rotor_a(j), rb = bodies_[j.b].rotor;
  const Bivector<N> plane_a = rotate(ra, outer<N>(def.plane_u_a, def.plane_v_a));
  const Bivector<N> plane_b = rotate(rb, outer<N>(def.plane_u_b, def.plane_v_b));
  if ((plane_a - plane_b).norm() > 1e-6)
    throw Error("add_joint: the revolute joint's planes of body_a and body_b are not the same plane now (they differ by " +
                std::to_string((plane_a - plane_b).norm()) + "); the angle is measured from where they meet");
  if (!(std::isfinite(def.lower_angle) && std::isfinite(def.upper_angle) && def.lower_angle <= def.upper_angle))
    throw Error("add_joint: lower_angle and upper_angle must be finite, lower <= upper (rad)");
  if (!std::isfinite(def.motor_speed)) throw Error("add_joint: motor_speed must be finite (rad/s)");
  if (!(std::isfinite(def.max_motor_torque) && def.max_motor_torque >= 0.0))
    throw Error("add_joint: max_motor_torque must be finite and >= 0 (N m)");
  j.reference = reverse(ra) * rb;
  j.plane_local = outer<N>(def.plane_u_a, def.plane_v_a);
  j.u_a = def.plane_u_a;
  j.v_a = def.plane_v_a;
  j.u_b = def.plane_u_b;
  const Vec<N> ub = rotate(rb, def.plane_u_b);
  j.angle_offset = std::atan2(ub.dot(rotate(ra, def.plane_v_a)), ub.dot(rotate(ra, def.plane_u_a)));
  j.limit = def.limit;
  j.lower_angle = def.lower_angle;
  j.upper_angle = def.upper_angle;
  j.motor = def.motor;
  j.motor_speed = def.motor_speed;
  j.max_motor_torque = def.max_motor_torque;
  return insert_joint(j);
}

template <int N>
JointId World<N>::add_joint(const PrismaticJointDef<N>& def) {
  contact::JointConstraint<N> j = joint_bodies(def, JointType::Prismatic);
  if (!(all_finite(def.axis_a) && std::abs(def.axis_a.norm() - 1.0) < 1e-9))
    throw Error("add_joint: a prismatic joint's axis_a must be a unit vector (to 1e-9)");
  if (!(std::isfinite(def.lower_translation) && std::isfinite(def.upper_translation) &&
        def.lower_translation <= def.upper_translation))
    throw Error("add_joint: lower_translation and upper_translation must be finite, lower <= upper (m)");
  if (!std::isfinite(def.motor_speed)) throw Error("add_joint: motor_speed must be finite (m/s)");
  if (!(std::isfinite(def.max_motor_force) && def.max_motor_force >= 0.0))
    throw Error("add_joint: max_motor_force must be finite and >= 0 (N)");
  const Rotor<N> ra = joint_rotor_a(j);
  const Body<N>& b = bodies_[j.b];
  const Vec<N> anchor_a = j.a >= 0 ? Vec<N>(bodies_[j.a].center + rotate(ra, j.local_a)) : j.local_a;
  j.reference = reverse(ra) * b.rotor;
  j.axis_local = def.axis_a;
  j.axis = rotate(ra, def.axis_a);
  j.translation = j.axis.dot(b.center + rotate(b.rotor, j.local_b) - anchor_a);
  j.limit = def.limit;
  j.lower_translation = def.lower_translation;
  j.upper_translation = def.upper_translation;
  j.motor = def.motor;
  j.motor_speed = def.motor_speed;
  j.max_motor_force = def.max_motor_force;
  return insert_joint(j);
}

template <int N>
JointId World<N>::add_joint(const WeldJointDef<N>& def) {
  contact::JointConstraint<N> j = joint_bodies(def, JointType::Weld);
  if (!(std::isfinite(def.frequency) && def.frequency >= 0.0)) throw Error("add_joint: frequency must be finite and >= 0 (Hz)");
  if (!(std::isfinite(def.damping_ratio) && def.damping_ratio >= 0.0))
    throw Error("add_joint: damping_ratio must be finite and >= 0");
  j.reference = reverse(joint_rotor_a(j)) * bodies_[j.b].rotor;
  j.spring = def.frequency > 0.0;
  j.frequency = def.frequency;
  j.damping_ratio = def.damping_ratio;
  return insert_joint(j);
}

template <int N>
Bivector<N> World<N>::joint_torque(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  const double h = contact_->joints.h;
  return h > 0.0 ? Bivector<N>(contact::joint_turn_impulse(j) * (1.0 / h)) : Bivector<N>{};
}

template <int N>
double World<N>::joint_angle(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  if (j.type != JointType::Revolute) throw Error("joint_angle: joint " + std::to_string(id.index) + " is not a revolute joint");
  return contact::joint_angle_now(j, bodies_);
}

template <int N>
double World<N>::joint_translation(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  if (j.type != JointType::Prismatic)
    throw Error("joint_translation: joint " + std::to_string(id.index) + " is not a prismatic joint");
  return j.translation;
}

template <int N>
void World<N>::remove_joint(JointId id) {
  auto& js = contact_->joints;
  const std::size_t slot = check(id);
  contact::JointConstraint<N>& j = js.slots[slot];
  if (j.a >= 0 && !j.collide_connected) {
    const auto at = std::lower_bound(js.no_collide.begin(), js.no_collide.end(), joined_key(j.a, j.b));
    js.no_collide.erase(at);  // (one of the pair's keys: each joint that joins them added one)
  }
  if (j.a >= 0) contact_->islands.wake_island(j.a);
  contact_->islands.wake_island(j.b);
  const std::uint32_t generation = j.generation;
  j = contact::JointConstraint<N>{};
  j.generation = generation;
  js.free_slots.push_back(std::uint32_t(slot));
  std::push_heap(js.free_slots.begin(), js.free_slots.end(), std::greater<>{});
}

template <int N>
bool World<N>::has_joint(JointId id) const {
  const auto& slots = contact_->joints.slots;
  return id.index < slots.size() && slots[id.index].live && slots[id.index].generation == id.generation;
}

template <int N>
int World<N>::joint_count() const {
  int count = 0;
  for (const auto& j : contact_->joints.slots) count += j.live ? 1 : 0;
  return count;
}

template <int N>
std::vector<JointId> World<N>::joint_ids() const {
  const auto& slots = contact_->joints.slots;
  std::vector<JointId> ids;
  for (std::size_t i = 0; i < slots.size(); ++i)
    if (slots[i].live) ids.push_back(JointId{std::uint32_t(i), slots[i].generation});
  return ids;
}

template <int N>
JointGeometry<N> World<N>::joint_geometry(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  JointGeometry<N> g;
  g.type = j.type;
  if (j.a >= 0) g.body_a = BodyId{std::uint32_t(j.a)};
  g.body_b = BodyId{std::uint32_t(j.b)};
  g.anchor_a = joint_anchor_a(id);
  g.anchor_b = joint_anchor_b(id);
  const Rotor<N> ra = joint_rotor_a(j);
  if (j.type == JointType::Revolute) {
    g.plane_u = rotate(ra, j.u_a);
    g.plane_v = rotate(ra, j.v_a);
    g.plane_u_b = rotate(bodies_[j.b].rotor, j.u_b);
  }
  if (j.type == JointType::Prismatic) g.axis = rotate(ra, j.axis_local);
  return g;
}

template <int N>
JointType World<N>::joint_type(JointId id) const {
  return contact_->joints.slots[check(id)].type;
}

template <int N>
Vec<N> World<N>::joint_anchor_a(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  if (j.a < 0) return j.local_a;
  return bodies_[j.a].center + rotate(bodies_[j.a].rotor, j.local_a);
}

template <int N>
Vec<N> World<N>::joint_anchor_b(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  return bodies_[j.b].center + rotate(bodies_[j.b].rotor, j.local_b);
}

template <int N>
Vec<N> World<N>::joint_force(JointId id) const {
  const contact::JointConstraint<N>& j = contact_->joints.slots[check(id)];
  const double h = contact_->joints.h;
  return h > 0.0 ? Vec<N>(contact::joint_impulse(j) / h) : Vec<N>(Vec<N>::Zero());
}

#define WEDGE_INSTANTIATE(N) \
  template std::uint32_t World<N>::check(JointId) const; \
  template contact::JointConstraint<N> World<N>::joint_bodies(const JointBodies<N>&, JointType) const; \
  template JointId World<N>::insert_joint(const contact::JointConstraint<N>&); \
  template JointId World<N>::add_joint(const PointJointDef<N>&); \
  template JointId World<N>::add_joint(const DistanceJointDef<N>&); \
  template Rotor<N> World<N>::joint_rotor_a(const contact::JointConstraint<N>&) const; \
  template JointId World<N>::add_joint(const RevoluteJointDef<N>&); \
  template JointId World<N>::add_joint(const PrismaticJointDef<N>&); \
  template JointId World<N>::add_joint(const WeldJointDef<N>&); \
  template Bivector<N> World<N>::joint_torque(JointId) const; \
  template double World<N>::joint_angle(JointId) const; \
  template double World<N>::joint_translation(JointId) const; \
  template void World<N>::remove_joint(JointId); \
  template bool World<N>::has_joint(JointId) const; \
  template int World<N>::joint_count() const; \
  template std::vector<JointId> World<N>::joint_ids() const; \
  template JointGeometry<N> World<N>::joint_geometry(JointId) const; \
  template JointType World<N>::joint_type(JointId) const; \
  template Vec<N> World<N>::joint_anchor_a(JointId) const; \
  template Vec<N> World<N>::joint_anchor_b(JointId) const; \
  template Vec<N> World<N>::joint_force(JointId) const;
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
