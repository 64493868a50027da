// Time of impact of two moving convex shapes by conservative advancement (Mirtich 1996; the rotational
// bound of Zhang, Redon, Lee & Kim 2007), in any dimension N.
//
// Each shape moves over a sweep: its centre of mass along a straight line and its orientation by a
// constant world-frame turn, q(t) = exp(t B) q0 for t in [0, 1], B = log(q1 q0~). From a time t where
// the shapes are d apart with closest points along the unit n (from a to b), no point can approach the
// other shape along n faster, per unit of t, than
//     mu = (dc_a - dc_b) . n  +  2 |B_a| r_a  +  2 |B_b| r_b,
// where dc is the centre's displacement over the sweep and r the shape's farthest point from its
// centre: a simple turn exp(B) rotates by the angle 2|B|, and a general one (commuting simple parts of
// norms b_i, sum b_i^2 = |B|^2) by at most that in each of its planes, so a point r from the centre
// moves at most 2|B| r. The projection of the two shapes on the fixed n stays a lower bound of their
// distance, so they cannot come within `target` of each other before t + (d - target) / mu; t advances
// by that much until the gap is within `tolerance` of the target (an impact) or t passes 1 (none).
// Every t it passes through is therefore safe: at the t returned the shapes are at least about
// `target` apart, never overlapping.
#pragma once

#include "wedge/collision/manifold.hpp"
#include "wedge/ga/types.hpp"
#include "wedge/shape.hpp"

namespace wedge {

// A body's motion over one step, as time of impact reads it (t in [0, 1]).
template <int N>
struct Sweep {
  Vec<N> local_center = Vec<N>::Zero();  // m, the centre of mass in the body frame
  Vec<N> c0 = Vec<N>::Zero();            // m, world centre of mass at t = 0
  Vec<N> c1 = Vec<N>::Zero();            // m, at t = 1
  Rotor<N> q0 = Rotor<N>::identity();    // body -> world at t = 0
  Bivector<N> turn{};                    // world frame: q(t) = exp(t turn) q0

  // A sweep that stays put.
  static Sweep still(const Vec<N>& center, const Rotor<N>& rotor, const Vec<N>& local_center = Vec<N>::Zero());
  // The sweep from one pose to another (centre of mass and rotor at t = 0 and at t = 1), turning the
  // short way (the log's principal angles, each at most pi).
  static Sweep between(const Vec<N>& c0, const Rotor<N>& q0, const Vec<N>& c1, const Rotor<N>& q1,
                       const Vec<N>& local_center = Vec<N>::Zero());

  Vec<N> center(double t) const { return c0 + t * (c1 - c0); }
  Rotor<N> rotor(double t) const;
  // Where the body frame is at t (x_world = position + rotation x_body).
  Transform<N> transform(double t) const;
};

struct TimeOfImpactSettings {
  double target = 0.005;      // m: the gap at which the shapes count as touching
  double tolerance = 0.001;   // m: an impact is reported once the gap is below target + tolerance
  int max_iterations = 64;    // advancements; if they run out, the t reached (safe) is reported
};

enum class ImpactState {
  Separated,     // no impact for t in [0, 1]
  Hit,           // the gap reached target + tolerance at t
  Overlapping,   // the shapes are already within the target at t = 0 (t = 0)
  OutOfIterations,  // max_iterations ran out at t: the shapes are still apart there, but come close
};

template <int N>
struct TimeOfImpact {
  ImpactState state = ImpactState::Separated;
  double t = 1.0;          // the time of impact, in [0, 1] (1 when Separated)
  // The gap at t (for Hit and OutOfIterations): m, its closest points (world) and the unit normal from a
  // towards b.
  double distance = 0.0;
  Vec<N> point_a = Vec<N>::Zero(), point_b = Vec<N>::Zero();
  Vec<N> normal = Vec<N>::Zero();
  int iterations = 0;  // advancements made
};

// The first t at which shape a (on sweep_a) comes within settings.target of shape b (on sweep_b). At
// most one of the two may be a half-space, and its sweep must stay put (static).
template <int N>
TimeOfImpact<N> time_of_impact(const Shape<N>& a, const Sweep<N>& sweep_a, const Shape<N>& b, const Sweep<N>& sweep_b,
                               const TimeOfImpactSettings& settings = {});

// The gap between two shapes (0 when they touch or overlap), its closest points and their direction
// from a towards b. At most one may be a half-space.
template <int N>
struct ShapeDistance {
  double distance = 0.0;
  Vec<N> point_a = Vec<N>::Zero(), point_b = Vec<N>::Zero();  // m, world: the closest points
  Vec<N> normal = Vec<N>::Zero();  // unit, (point_b - point_a) / distance; zero when touching
};
template <int N>
ShapeDistance<N> shape_distance(const Shape<N>& a, const Transform<N>& ta, const Shape<N>& b, const Transform<N>& tb);

}  // namespace wedge
