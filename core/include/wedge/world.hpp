// The world: bodies, global settings and the time step.
//
// World::step(h) runs named stages in a fixed order (see world.cpp):
//   integrate_velocities  forces, gravity, drag; the gyroscopic term implicitly (one Newton step)
//   integrate_positions   x += h v, R <- exp(-h w / 2) R, then rotor repair
//   clear_forces
// Later stages (collision, contact, shock propagation) slot in between the first two. Input is applied
// only between steps, through the apply_* calls. Bodies are stored in creation order and every loop
// runs in that order, so the same inputs give bit-identical states.
#pragma once

#include <cstdint>
#include <vector>

#include "wedge/body.hpp"

namespace wedge {

// How the gyroscopic term of Euler's equation is integrated (both implicit, by Newton steps).
enum class GyroscopicMethod : std::uint8_t {
  // Implicit midpoint, two Newton iterations: conserves energy and |L| of a free body to round-off at
  // game time steps (the default).
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
};

struct BodyId {
  std::uint32_t index = 0;
};

template <int N>
class World {
 public:
  explicit World(const WorldSettings<N>& settings = {});

  BodyId add_body(const BodyDef<N>& def);
  int body_count() const { return int(bodies_.size()); }
  const Body<N>& body(BodyId id) const { return bodies_[id.index]; }
  Body<N>& body(BodyId id) { return bodies_[id.index]; }
  const std::vector<Body<N>>& bodies() const { return bodies_; }
  const std::string& name(BodyId id) const { return names_[id.index]; }
  const WorldSettings<N>& settings() const { return settings_; }
  WorldSettings<N>& settings() { return settings_; }

  // Input between steps. Forces and torques act during the next step only.
  void apply_force(BodyId id, const Vec<N>& force);                         // N, at the centre
  void apply_force_at(BodyId id, const Vec<N>& force, const Vec<N>& point);  // N, world point
  void apply_torque(BodyId id, const Bivector<N>& torque);                   // N m, world frame
  // Impulses change velocities at once: v += j/m, w += I'^-1 (r ^ j) = I'^-1 [r]_* j.
  void apply_impulse_at(BodyId id, const Vec<N>& impulse, const Vec<N>& point);  // N s
  void apply_angular_impulse(BodyId id, const Bivector<N>& impulse);              // N m s

  void step(double h);
  std::int64_t step_count() const { return steps_; }
  double time() const { return time_; }

  // Diagnostics over dynamic bodies (static and kinematic ones carry no momentum).
  double kinetic_energy() const;
  double potential_energy() const;  // -m g . x, zero at the origin
  Vec<N> linear_momentum() const;
  Bivector<N> angular_momentum() const;  // about the world origin: sum of x ^ m v + I' w
  // FNV-1a over the bytes of every body's centre, rotor, velocity and angular velocity.
  std::uint64_t state_hash() const;

 private:
  void integrate_velocities(double h);
  void integrate_positions(double h);
  void clear_forces();

  WorldSettings<N> settings_;
  std::vector<Body<N>> bodies_;
  std::vector<std::string> names_;  // cold data, apart from the hot state
  std::int64_t steps_ = 0;
  double time_ = 0.0;
};

// One implicit step of the torque-free Euler equation I dw/dt - w x I w = 0 in the body frame, solved
// by Newton's method from w (Catto 2015, generalised with the bivector commutator [a]x b = a x b).
// With m = (1-t) w + t w' (t = 1: implicit Euler, t = 1/2: implicit midpoint) each iteration solves
//   g(w') = I (w' - w) - h m x I m = 0,   J = I - t h ([m]x I - [I m]x),   w' <- w' - J^-1 g(w').
// The midpoint result never gains energy: if unconverged iterations raised w'.I w', it is scaled back.
template <int N>
Bivector<N> gyroscopic_step(const BivMat<N>& inertia, const Bivector<N>& w_body, double h,
                            GyroscopicMethod method = GyroscopicMethod::ImplicitMidpoint);

}  // namespace wedge
