// A joint's slot (internal): what World::add_joint derived from its definition, what the current
// sub-step derived from the bodies' poses (joints.cpp, prepare_joints), and the accumulated impulses
// that warm start the next sub-step and step.
#pragma once

#include <cstdint>
#include <limits>

#include "wedge/ga/types.hpp"
#include "wedge/joint.hpp"
#include "wedge/softness.hpp"

namespace wedge::contact {

template <int N>
struct JointConstraint {
  JointType type = JointType::Point;
  std::uint32_t generation = 0;
  bool live = false;
  int a = -1, b = 0;                         // body indices; a = -1: the world
  // m: each anchor from its body's centre of mass, in the body's frame (a = -1: the world point itself)
  Vec<N> local_a = Vec<N>::Zero(), local_b = Vec<N>::Zero();
  bool collide_connected = false;
  // Distance joints (DistanceJointDef): m, and the spring's Hz and damping ratio.
  double length = 0.0, min_length = 0.0, max_length = std::numeric_limits<double>::infinity();
  bool spring = false;
  double frequency = 0.0, damping_ratio = 0.0;

  // This sub-step (prepare_joints).
  bool active = false;                       // live, with a body that moves
  Vec<N> ra = Vec<N>::Zero(), rb = Vec<N>::Zero();  // m, world: the anchors from the centres of mass
  Vec<N> separation = Vec<N>::Zero();        // m, world: anchor b - anchor a
  Mat<N> mass = Mat<N>::Zero();              // point: K^-1, K the anchors' relative effective mass matrix
  Vec<N> axis = Vec<N>::Zero();              // distance: the unit direction from anchor a to anchor b
  double distance = 0.0;                     // m, distance: |separation|
  double axial_mass = 0.0;                   // kg, distance: 1 / (axis^T K axis)
  Softness spring_soft;                      // distance with a spring: its coefficients for the sub-step

  // Accumulated impulses (N s) on body b (body a takes their opposite), kept between sub-steps and
  // steps: the warm start.
  Vec<N> linear_impulse = Vec<N>::Zero();    // point
  double impulse = 0.0;                      // distance: along the axis (rigid, or the spring)
  double lower_impulse = 0.0, upper_impulse = 0.0;  // distance: the limits' (>= 0; the upper pulls)
};

}  // namespace wedge::contact
