// The world: bodies, global settings and the time step.
//
// World::step(h) runs named stages in a fixed order (see world.cpp and core/src/contact/). With the
// default contact solver, the soft step (ContactSettings::solver, docs/contact.md):
//   find_contacts         broad phase, narrow phase at the current positions, the step's constraints
//   soft_step             per sub-step of h / substeps: integrate_velocities, solve (soft contacts),
//                         integrate_positions, relax; then restitution
//   solve_continuous      fast bodies swept against static shapes, put back at the time of impact
//   update_islands        islands of touching bodies; still islands fall asleep
//   report_contact_events pairs that began or stopped touching
//   clear_forces
// With the paper's solver (Guendelman, Bridson & Fedkiw 2003, as in the paper's section 6), the middle
// stages are instead
//   process_collisions    restitution impulses for contacts that close within the step
//   integrate_velocities  forces, gravity, drag; the gyroscopic term implicitly
//   process_contacts      restitution 0, then shock propagation up the contact graph, then
//                         split-impulse position correction
//   integrate_positions   x += h v, R <- exp(-h w / 2) R, then rotor repair
// and then solve_continuous as above.
// Input is applied only between steps, through the apply_* calls, grabs and set_gravity (which wake the
// bodies they move). Bodies are
// stored in creation order and every loop runs in that order, so the same inputs give bit-identical
// states.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "wedge/body.hpp"
#include "wedge/contact.hpp"
#include "wedge/grab.hpp"
#include "wedge/joint.hpp"
#include "wedge/profile.hpp"

namespace wedge {

// How the gyroscopic term of Euler's equation is integrated (both implicit).
enum class GyroscopicMethod : std::uint8_t {
  // Implicit midpoint, solved to round-off (by fixed-point iteration for a diagonal inertia, by two Newton
  // iterations otherwise): conserves energy and |L| of a free body to round-off at game time steps (the
  // default).
  ImplicitMidpoint,
  // Implicit Euler, one Newton step: the paper's and Catto's choice; unconditionally stable but it
  // dissipates energy at a rate proportional to h (e.g. -17% in 30 s for a 3 rad/s cuboid at 1/120 s).
  ImplicitEuler,
};

template <int N>
struct WorldSettings {
  Vec<N> gravity = Vec<N>::Zero();  // m/s^2, any direction in R^N
  bool gyroscopic = true;           // integrate the w x I'w term (off only for experiments)
  GyroscopicMethod gyroscopic_method = GyroscopicMethod::ImplicitMidpoint;
  int rotor_repair_interval = 1;    // steps between rotor repairs by factorisation (>= 1)
  // Threads a step may use, 1..64, the calling thread included. The soft step splits each colour of
  // constraints and the per-body loops between them; the state after a step is bit-identical for any
  // count (docs/contact.md). Above the processor count it only costs.
  int workers = 1;
  ContactSettings contact;          // collision and contact processing, sleeping
};

// A body found by World::query_point: the one containing the point, else the nearest.
template <int N>
struct BodyPointHit {
  BodyId body;
  bool inside = false;             // the point lies in the body (boundary included)
  double distance = 0.0;           // m, 0 when inside
  Vec<N> closest = Vec<N>::Zero();  // m, world: the body's point nearest to the query point
};

// The first body a ray meets (World::ray_cast).
template <int N>
struct RayHit {
  BodyId body;
  double distance = 0.0;            // m along the (unit) direction; 0 if the origin is inside the body
  Vec<N> point = Vec<N>::Zero();    // m, world
  Vec<N> normal = Vec<N>::Zero();   // unit, the body's outward normal there (-direction from inside)
};

namespace contact {
template <int N>
struct ContactState;
template <int N>
struct JointConstraint;
}

template <int N>
class World {
 public:
  static constexpr int dimension = N;
  explicit World(const WorldSettings<N>& settings = {});
  ~World();
  World(const World& other);
  World& operator=(const World& other);
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  BodyId add_body(const BodyDef<N>& def);
  int body_count() const { return int(bodies_.size()); }
  // Every call taking a BodyId checks it and throws wedge::Error for an id this world never gave out.
  // The references body() and bodies() return stay valid until the next add_body, which may move every
  // body; keep the BodyId, not the reference, across it. Writing a body's state through body() (a tool
  // posing bodies to draw them) bypasses waking and the checks: input goes through the apply_* calls.
  const Body<N>& body(BodyId id) const { return bodies_[check(id)]; }
  Body<N>& body(BodyId id) { return bodies_[check(id)]; }
  const std::vector<Body<N>>& bodies() const { return bodies_; }
  const std::string& name(BodyId id) const { return names_[check(id)]; }
  const WorldSettings<N>& settings() const { return settings_; }
  // Replaces the settings between steps, checked as the constructor checks them: throws wedge::Error
  // naming the field, and then the world is unchanged. A new gravity wakes the sleeping bodies, as
  // set_gravity does.
  void set_settings(const WorldSettings<N>& settings);
  // The same for a change to the current settings: world.update_settings([](auto& s) { s.workers = 2; }).
  template <class Change>
  void update_settings(Change&& change) {
    WorldSettings<N> s = settings_;
    change(s);
    set_settings(s);
  }
  const Shape<N>* shape(BodyId id) const { return shapes_[check(id)].get(); }
  const Material& material(BodyId id) const { return materials_[check(id)]; }
  // The application's own tag for a body (an index into its tables, a pointer's bits); never read here.
  std::uint64_t user_data(BodyId id) const { return user_data_[check(id)]; }
  void set_user_data(BodyId id, std::uint64_t data) { user_data_[check(id)] = data; }

  // Gravity between steps (m/s^2): throws wedge::Error for a non-finite vector; a change wakes every
  // sleeping body, since bodies at rest under the old gravity need not be at rest under the new one.
  const Vec<N>& gravity() const { return settings_.gravity; }
  void set_gravity(const Vec<N>& g);

  // Sleeping: a body at rest with its island is not simulated until something touches it or input is
  // applied to it. Changing a body's state through body(id) does not wake it; call wake(id).
  bool is_awake(BodyId id) const;
  void wake(BodyId id);  // wakes the island it sleeps in

  // Kinematic bodies (grabs, paddles): sets the velocities that carry the body to the pose (position of
  // the body frame, rotor) in one step of h seconds.
  void move_kinematic(BodyId id, const Vec<N>& position, const Rotor<N>& rotor, double h);

  // Input between steps. Forces and torques act during the next step only.
  void apply_force(BodyId id, const Vec<N>& force);                         // N, at the centre
  void apply_force_at(BodyId id, const Vec<N>& force, const Vec<N>& point);  // N, world point
  void apply_torque(BodyId id, const Bivector<N>& torque);                   // N m, world frame
  // Impulses change velocities at once: v += j/m, w += I'^-1 (r ^ j) = I'^-1 [r]_* j.
  void apply_impulse_at(BodyId id, const Vec<N>& impulse, const Vec<N>& point);  // N s
  void apply_angular_impulse(BodyId id, const Bivector<N>& impulse);              // N m s

  // Grabs (wedge/grab.hpp): a soft constraint pulling a point of a dynamic body toward a target, solved
  // with the contacts. add_grab throws wedge::Error for a body that is not dynamic or invalid settings;
  // the other calls throw for an id that was removed. Setting a target wakes the body.
  GrabId add_grab(const GrabDef<N>& def);
  void set_grab_target(GrabId id, const Vec<N>& target, const Vec<N>& target_velocity);
  void remove_grab(GrabId id);
  bool has_grab(GrabId id) const;
  const GrabDef<N>& grab(GrabId id) const;
  Vec<N> grab_point(GrabId id) const;  // m, world: where the grabbed point of the body is now

  // Joints (wedge/joint.hpp), solved by the soft step only. add_joint throws wedge::Error for an invalid
  // definition (naming the field) and under the paper's solver (ContactSolver::Paper); the other calls
  // throw for an id that was removed. Adding or removing a joint wakes its bodies.
  JointId add_joint(const PointJointDef<N>& def);
  JointId add_joint(const DistanceJointDef<N>& def);
  JointId add_joint(const RevoluteJointDef<N>& def);
  JointId add_joint(const PrismaticJointDef<N>& def);
  JointId add_joint(const WeldJointDef<N>& def);
  void remove_joint(JointId id);
  bool has_joint(JointId id) const;
  int joint_count() const;  // live joints
  std::vector<JointId> joint_ids() const;  // the live joints, lowest slot first
  JointGeometry<N> joint_geometry(JointId id) const;  // anchors, plane or axis, world, as placed now
  JointType joint_type(JointId id) const;
  Vec<N> joint_anchor_a(JointId id) const;  // m, world: where each anchor is now
  Vec<N> joint_anchor_b(JointId id) const;
  // N, world: the force the joint applied to body_b in the last sub-step (body_a took its opposite);
  // zero before the joint's first step.
  Vec<N> joint_force(JointId id) const;
  // N m, world: the torque the joint's angular rows applied to body_b in the last sub-step (besides
  // joint_force at its anchor); zero for point and distance joints.
  Bivector<N> joint_torque(JointId id) const;
  // rad: a revolute joint's angle, body_b's turn relative to body_a in the plane since the joint was
  // added (u toward v), as of the last step; throws for another kind of joint.
  double joint_angle(JointId id) const;
  // m: a prismatic joint's translation, anchor_b's distance from anchor_a along the axis, as of the last
  // step (before the first, when the joint was added); throws for another kind of joint.
  double joint_translation(JointId id) const;

  // Queries on the state (shapes as placed now; candidates culled by the broad phase's boxes of the
  // last step, which hold every body that has not been moved by hand since).
  // The body containing x (the lowest index if several), else the nearest within max_distance (ties:
  // the lower index); static bodies only if include_static.
  std::optional<BodyPointHit<N>> query_point(const Vec<N>& x, double max_distance, bool include_static = true) const;
  // The first body along origin + t direction, 0 <= t <= max_distance (direction need not be unit).
  std::optional<RayHit<N>> ray_cast(const Vec<N>& origin, const Vec<N>& direction, double max_distance,
                                    bool include_static = true) const;

  void step(double h);
  std::int64_t step_count() const { return steps_; }
  // Where the last step's time went, stage by stage (wedge/profile.hpp); zero before the first step.
  const StepProfile& profile() const { return profile_; }
  double time() const { return time_ + time_error_; }  // s: the sum of the steps taken

  // Diagnostics over dynamic bodies (static and kinematic ones carry no momentum).
  double kinetic_energy() const;
  double potential_energy() const;  // -m g . x, zero at the origin
  Vec<N> linear_momentum() const;
  Bivector<N> angular_momentum() const;  // about the world origin: sum of x ^ m v + I' w
  // FNV-1a over the bytes of every body's centre, rotor, velocity and angular velocity.
  std::uint64_t state_hash() const;

  // What the last step did with contacts (arrays, sorted by pair; empty before the first step).
  const std::vector<ContactBeginEvent<N>>& contact_begin_events() const;
  const std::vector<ContactEndEvent>& contact_end_events() const;
  // Every pair with contact points in the last step, sorted by (a, b) (built on demand).
  std::vector<ContactInfo<N>> contacts() const;

 private:
  void find_contacts(double h);
  void soft_step(double h);
  void process_collisions(double h);
  void integrate_velocities(double h);
  void process_contacts(double h);
  void integrate_positions(double h);
  void update_islands(double h);
  void report_contact_events();
  void clear_forces();
  std::uint32_t check(BodyId id) const;
  std::uint32_t check(GrabId id) const;
  std::uint32_t check(JointId id) const;
  // The checks every joint shares (bodies, anchors, the solver), then the joint in the lowest free slot.
  contact::JointConstraint<N> joint_bodies(const JointBodies<N>& def, JointType type) const;
  Rotor<N> joint_rotor_a(const contact::JointConstraint<N>& joint) const;  // body a's rotor (the world's: 1)
  JointId insert_joint(const contact::JointConstraint<N>& joint);

  WorldSettings<N> settings_;
  std::vector<Body<N>> bodies_;
  std::vector<std::string> names_;  // cold data, apart from the hot state
  std::vector<std::shared_ptr<const Shape<N>>> shapes_;
  std::vector<Material> materials_;
  std::vector<std::uint64_t> user_data_;
  std::unique_ptr<contact::ContactState<N>> contact_;
  std::int64_t steps_ = 0;
  StepProfile profile_;
  double time_ = 0.0, time_error_ = 0.0;  // (compensated summation)
};

// One implicit step of the torque-free Euler equation I dw/dt - w x I w = 0 in the body frame (Catto 2015,
// generalised with the bivector commutator [a]x b = a x b). With m = (1-t) w + t w' (t = 1: implicit Euler,
// t = 1/2: implicit midpoint) it solves g(w') = I (w' - w) - h m x I m = 0.
// - Midpoint, diagonal I (a principal body frame, as every box has): fixed-point iteration
//   w' <- w + h I^-1 (m x I m) to round-off, which contracts by about h |w| for any rigid body's moments
//   (integrate.cpp says why), so a sub-step converges in about 8 commutators and no matrix is formed.
// - Otherwise (a full inertia, the paper's implicit Euler, or an iteration that has not converged in 24
//   rounds) by Newton's method from w: J = I - t h ([m]x I - [I m]x), w' <- w' - J^-1 g(w'), with J taken
//   at w' = w and factorised once (implicit Euler: one iteration; midpoint: two).
// The midpoint result never gains energy: if round-off or unconverged iterations raised w'.I w', it is
// scaled back.
template <int N>
Bivector<N> gyroscopic_step(const BivMat<N>& inertia, const Bivector<N>& w_body, double h,
                            GyroscopicMethod method = GyroscopicMethod::ImplicitMidpoint);

}  // namespace wedge
