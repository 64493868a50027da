// Joints: constraints between two bodies, or a body and the world, solved with the contacts in every
// sub-step of the soft step (docs/joints.md). Each kind has its own definition struct; World::add_joint
// checks it and returns a JointId.
//
//   PointJointDef     ball and socket: the two anchors coincide, every relative rotation is free.
//   DistanceJointDef  the anchors a fixed distance apart (a massless rod), or a rope between a minimum
//                     and a maximum length, or a spring; every rotation is free.
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

enum class JointType : std::uint8_t { Point, Distance };

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

// A handle to a joint: its slot and the generation it was made in, so a removed joint's id is refused.
struct JointId {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;
  friend bool operator==(JointId a, JointId b) { return a.index == b.index && a.generation == b.generation; }
};

}  // namespace wedge
