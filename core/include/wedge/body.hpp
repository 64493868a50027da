// Rigid bodies: definition (what a user fills in) and state (what the step touches).
//
// Frames: the body frame is the frame the shape is given in. `position` and `rotor` place that frame in
// the world (x_world = position + R x_body ~R). Dynamics act on the centre of mass, so the state also
// keeps the world centre; `velocity` is the centre's velocity. Angular velocity and angular momentum
// are world-frame bivectors (components e01, e02, .., e12, ..). SI units throughout.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "wedge/contact.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/shape.hpp"

namespace wedge {

enum class BodyType : std::uint8_t {
  Static,     // never moves; infinite mass
  Kinematic,  // moves with its given velocities (grabs, paddles); infinite mass, unaffected by forces
  Dynamic,    // moved by forces, torques and impulses
};

template <int N>
struct BodyDef {
  std::string name;
  BodyType type = BodyType::Dynamic;
  Vec<N> position = Vec<N>::Zero();                      // m, origin of the body frame
  Rotor<N> rotor = Rotor<N>::identity();                 // body -> world
  Vec<N> velocity = Vec<N>::Zero();                      // m/s, of the centre of mass
  Bivector<N> angular_velocity{};                        // rad/s, world frame
  double mass = 1.0;                                     // kg, > 0 for dynamic bodies
  Vec<N> local_center = Vec<N>::Zero();                  // m, centre of mass in the body frame
  BivMat<N> inertia = BivMat<N>::Identity();             // kg m^2, body frame, about the centre of mass
  double linear_drag = 0.0;                              // 1/s, dv/dt = -c v (air drag), >= 0
  double angular_drag = 0.0;                             // 1/s, dw/dt = -c w, >= 0
  // What the body collides as (in the body frame); null: it collides with nothing. Shared, so that a
  // thousand equal boxes hold one shape. A half-space is allowed on static bodies only.
  std::shared_ptr<const Shape<N>> shape;
  Material material;
  std::uint64_t user_data = 0;  // the application's own tag (World::user_data)
};

// Hot state first (read and written every step), mass data after.
template <int N>
struct Body {
  Vec<N> center = Vec<N>::Zero();    // m, world centre of mass
  Rotor<N> rotor = Rotor<N>::identity();
  Vec<N> velocity = Vec<N>::Zero();  // m/s
  Bivector<N> angular_velocity{};    // rad/s, world frame
  Vec<N> force = Vec<N>::Zero();     // N, accumulated until the end of the next step
  Bivector<N> torque{};              // N m, world frame, accumulated likewise

  BodyType type = BodyType::Dynamic;
  double mass = 0.0, inv_mass = 0.0;  // 0 and 0 for static and kinematic bodies
  Vec<N> local_center = Vec<N>::Zero();
  BivMat<N> inertia = BivMat<N>::Zero();      // body frame, about the centre
  BivMat<N> inv_inertia = BivMat<N>::Zero();  // body frame; zero for static and kinematic bodies
  double linear_drag = 0.0, angular_drag = 0.0;

  bool is_dynamic() const { return type == BodyType::Dynamic; }
  // Origin of the body frame in the world.
  Vec<N> position() const { return center - rotate(rotor, local_center); }
  // World inertia I' = [R]_2 I [R]_2^T (eq. 4) and its inverse.
  BivMat<N> world_inertia() const {
    const BivMat<N> r2 = bivector_matrix(rotor);
    return r2 * inertia * r2.transpose();
  }
  BivMat<N> world_inv_inertia() const {
    const BivMat<N> r2 = bivector_matrix(rotor);
    return r2 * inv_inertia * r2.transpose();
  }
  // World angular momentum about the centre of mass, L = I' w.
  Bivector<N> angular_momentum() const { return Bivector<N>::from(world_inertia() * angular_velocity.c); }
  // Velocity of the world point p: v + r . w with r = p - centre.
  Vec<N> velocity_at(const Vec<N>& p) const { return velocity + dot<N>(p - center, angular_velocity); }
  double kinetic_energy() const {
    if (!is_dynamic()) return 0.0;
    return 0.5 * mass * velocity.squaredNorm() + 0.5 * angular_velocity.c.dot(world_inertia() * angular_velocity.c);
  }
};

// Builds the state of a body from its definition; throws wedge::Error for invalid definitions
// (non-positive mass, inertia not symmetric positive definite, non-finite values, non-unit rotor).
template <int N>
Body<N> make_body(const BodyDef<N>& def);

}  // namespace wedge
