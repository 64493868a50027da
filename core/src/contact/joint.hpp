// A joint's slot (internal): what World::add_joint derived from its definition, what the step and its
// current sub-step derived from the bodies' poses (joints.cpp: prepare_joints once a step, the effective
// masses; each sub-step's placing, the lever arms and errors), and the accumulated impulses that warm
// start the next sub-step and step.
#pragma once

#include <cstdint>
#include <limits>

#include "wedge/ga/types.hpp"
#include "wedge/joint.hpp"
#include "wedge/softness.hpp"

namespace wedge::contact {

template <int N>
struct JointConstraint {
  // (The fields every sub-step's passes read come first, the point rows' in the first cache lines: a slot
  // is hundreds of bytes and a pass over a large world's joints is limited by memory.)
  JointType type = JointType::Point;
  bool live = false;
  bool active = false;                       // this step: live, with a body that moves (prepare_joints)
  bool angle_each_substep = false;           // revolute, this step: its angle taken at every placing
  bool spring = false;                       // distance: a spring (DistanceJointDef); weld: soft
  bool limit = false, motor = false;         // revolute, prismatic (distance limits: spring, min/max_length)
  bool collide_connected = false;
  std::uint32_t generation = 0;
  int a = -1, b = 0;                         // body indices; a = -1: the world
  // m: each anchor from its body's centre of mass, in the body's frame (a = -1: the world point itself)
  Vec<N> local_a = Vec<N>::Zero(), local_b = Vec<N>::Zero();

  // This sub-step (its placing): m, world: the anchors from the centres of mass (prismatic: ra reaches
  // anchor b, as the axis turns with a), and anchor b - anchor a.
  Vec<N> ra = Vec<N>::Zero(), rb = Vec<N>::Zero();
  Vec<N> separation = Vec<N>::Zero();
  Mat<N> mass = Mat<N>::Zero();              // this step: point: K^-1, K the anchors' relative effective
                                             // mass matrix; prismatic: the rows across the axis' (prepare_joint)
  // Accumulated impulses (N s) on body b (body a takes their opposite), kept between sub-steps and
  // steps: the warm start.
  Vec<N> linear_impulse = Vec<N>::Zero();    // point, revolute, weld; prismatic: across the axis

  // Revolute joints: the plane, a unit bivector in a's frame, two vectors in a's frame and one in b's (the
  // angle is u_b's turn from u_a toward v_a, less angle_offset, its value when added).
  Bivector<N> plane_local{};
  Vec<N> u_a = Vec<N>::Zero(), v_a = Vec<N>::Zero(), u_b = Vec<N>::Zero();
  double angle_offset = 0.0;
  double angle = 0.0;  // rad, revolute: the angle at the last placing that took it (unwrapped: it may pass pi)
  double lower_angle = 0.0, upper_angle = 0.0, motor_speed = 0.0, max_motor_torque = 0.0;  // rad, rad/s, N m
  // Revolute and weld joints: body b's orientation relative to a's when the joint was added, ~R_a R_b
  // (R_b with the world as a).
  Rotor<N> reference = Rotor<N>::identity();
  // Distance joints (DistanceJointDef): m, and the spring's Hz and damping ratio.
  double length = 0.0, min_length = 0.0, max_length = std::numeric_limits<double>::infinity();
  double frequency = 0.0, damping_ratio = 0.0;
  // Prismatic joints: the unit axis in a's frame, the translation limits (m), the motor's force limit
  // (N; its speed, m/s, is motor_speed), and the translation at the last placing (m).
  Vec<N> axis_local = Vec<N>::Zero();
  double lower_translation = 0.0, upper_translation = 0.0, max_motor_force = 0.0;
  double translation = 0.0;

  // The other joints' rows: the axes and planes this sub-step (its placing), the masses this step.
  Vec<N> axis = Vec<N>::Zero();              // distance: the unit direction from anchor a to anchor b;
                                             // prismatic: the axis, world
  double distance = 0.0;                     // m, distance: |separation|
  double axial_mass = 0.0;                   // kg, distance, prismatic: 1 / (axis^T K axis)
  Softness spring_soft;                      // distance with a spring, soft weld: its coefficients
  Bivector<N> plane{};                       // revolute: the plane, world (unit)
  double plane_mass = 0.0;                   // revolute: 1 / (p . (I_a^-1 + I_b^-1) p), the plane's row
  Bivector<N> turn{};                        // revolute, weld: the turn (rad) that would bring b where it belongs
  BivMat<N> angular_mass = BivMat<N>::Zero();  // revolute, weld: the angular rows' inverse effective mass

  // The other accumulated impulses.
  double impulse = 0.0;                      // distance: along the axis (rigid, or the spring)
  double lower_impulse = 0.0, upper_impulse = 0.0;  // distance, prismatic: the limits' (>= 0; the upper pulls)
  Bivector<N> angular_impulse{};             // N m s, revolute (out of the plane), prismatic, weld: on body b
  double motor_impulse = 0.0;                // N m s, revolute: the motor's, in the plane; N s, prismatic
  double lower_angle_impulse = 0.0, upper_angle_impulse = 0.0;  // N m s, revolute: the angle limits' (>= 0)
};

}  // namespace wedge::contact
