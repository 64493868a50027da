// Joints: constraints between two bodies, or a body and the world, solved with the contacts in every
// sub-step of the soft step (docs/joints.md). Each kind has its own definition struct; World::add_joint
// checks it and returns a JointId.
//
//   PointJointDef     ball and socket: the two anchors coincide, every relative rotation is free.
//   DistanceJointDef  the anchors a fixed distance apart (a massless rod), or a rope between a minimum
//                     and a maximum length, or a spring; every rotation is free.
//   RevoluteJointDef  a point joint whose bodies may turn relative to each other only in one plane (in 3D
//                     a hinge about the plane's normal; in 4D a door hinged on a 2-plane), with angle
//                     limits and a motor.
//   PrismaticJointDef a slider: body b may move relative to body a only along one axis, and may not turn
//                     relative to it; translation limits and a motor.
//   WeldJointDef      no relative motion at all, rigid or soft.
//
// Like contacts, a joint's position error is corrected by a stiff soft constraint (ContactSettings::
// joint_hertz and joint_damping_ratio) in the solve pass, and the relax pass removes the velocity that
// correction leaves, so a joint holds its bodies together without adding energy. The paper's contact
// solver (ContactSolver::Paper) has no joints: World refuses them there.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "wedge/contact.hpp"
#include "wedge/ga/types.hpp"

namespace wedge {

enum class JointType : std::uint8_t { Point, Distance, Revolute, Prismatic, Weld };

// What every joint has: the bodies and where on them it holds, in each body's own frame (the shape's
// frame, as BodyDef::position places it). Without body_a the joint holds body_b to the world, and
// anchor_a is a world point.
template <int N>
struct JointBodies {
  std::optional<BodyId> body_a;          // none: the world
  BodyId body_b;                         // a dynamic body (or kinematic, if body_a is dynamic)
  Vec<N> anchor_a = Vec<N>::Zero();      // m, body_a's frame (or world)
  Vec<N> anchor_b = Vec<N>::Zero();      // m, body_b's frame
  bool collide_connected = false;        // false: the two bodies never collide with each other
};

// Ball and socket: anchor_a and anchor_b stay at one point.
template <int N>
struct PointJointDef : JointBodies<N> {};

// The anchors stay `length` apart (a massless rod). With `spring` the length is instead a spring's rest
// length, of natural frequency `frequency` (0: no spring force at all, a rope) and damping ratio
// `damping_ratio`, and the distance is held between min_length and max_length.
template <int N>
struct DistanceJointDef : JointBodies<N> {
  double length = -1.0;          // m, > 0; negative: the anchors' distance when the joint is added
  bool spring = false;
  double frequency = 0.0;        // Hz, >= 0 (spring only)
  double damping_ratio = 0.0;    // >= 0, 1 is critical damping (spring only)
  double min_length = 0.0;       // m, >= 0 (spring only)
  double max_length = std::numeric_limits<double>::infinity();  // m, >= min_length (spring only)
};

// A point joint whose bodies may turn relative to each other only in one plane. The plane is given in
// each body's frame by two orthonormal vectors; the two must be the same plane when the joint is added,
// and the angle is measured from there: positive turns u toward v (body b relative to body a). With
// `limit` the angle stays in [lower_angle, upper_angle]; with `motor` the joint drives the relative
// angular speed in the plane toward motor_speed with at most max_motor_torque. In 2D the plane is the
// only one (the defaults, x and y), and this is Box2D's revolute joint.
template <int N>
struct RevoluteJointDef : JointBodies<N> {
  Vec<N> plane_u_a = Vec<N>::Unit(0), plane_v_a = Vec<N>::Unit(1);  // body_a's frame (world without body_a)
  Vec<N> plane_u_b = Vec<N>::Unit(0), plane_v_b = Vec<N>::Unit(1);  // body_b's frame
  bool limit = false;
  double lower_angle = 0.0, upper_angle = 0.0;  // rad, lower <= upper
  bool motor = false;
  double motor_speed = 0.0;       // rad/s, in the plane (u toward v)
  double max_motor_torque = 0.0;  // N m, >= 0
};

// A slider: anchor_b may move relative to body a only along `axis_a` through anchor_a, and body b keeps
// its orientation relative to a from when the joint is added. The translation is anchor_b's distance from
// anchor_a along the axis (0 where the anchors coincide). With `limit` it stays in [lower_translation,
// upper_translation]; with `motor` the joint drives the relative speed along the axis toward motor_speed
// with at most max_motor_force. Box2D's prismatic joint in 2D, Jolt's slider in 3D.
template <int N>
struct PrismaticJointDef : JointBodies<N> {
  Vec<N> axis_a = Vec<N>::Unit(0);  // unit, body_a's frame (world without body_a)
  bool limit = false;
  double lower_translation = 0.0, upper_translation = 0.0;  // m, lower <= upper
  bool motor = false;
  double motor_speed = 0.0;      // m/s, along the axis
  double max_motor_force = 0.0;  // N, >= 0
};

// No relative motion: the anchors coincide and the bodies keep their relative orientation from when the
// joint is added. With frequency > 0 the weld is a spring (linear and angular) of that natural frequency
// and damping ratio instead of rigid.
template <int N>
struct WeldJointDef : JointBodies<N> {
  double frequency = 0.0;      // Hz, >= 0: 0 is rigid
  double damping_ratio = 1.0;  // >= 0
};

// A handle to a joint: its slot and the generation it was made in, so a removed joint's id is refused.
// Where a joint is now, world frame (World::joint_geometry): what a viewer draws of it.
template <int N>
struct JointGeometry {
  JointType type = JointType::Point;
  std::optional<BodyId> body_a;  // none: the world
  BodyId body_b;
  Vec<N> anchor_a = Vec<N>::Zero(), anchor_b = Vec<N>::Zero();  // m
  // Revolute: the plane of rotation, body_a's two vectors (unit, orthogonal), and body_b's first vector,
  // which lies in the plane turned from plane_u by the joint's angle. Zero for other joints.
  Vec<N> plane_u = Vec<N>::Zero(), plane_v = Vec<N>::Zero(), plane_u_b = Vec<N>::Zero();
  Vec<N> axis = Vec<N>::Zero();  // prismatic: the axis (unit, body_a's); zero for other joints
};

struct JointId {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;
  friend bool operator==(JointId a, JointId b) { return a.index == b.index && a.generation == b.generation; }
};

}  // namespace wedge
