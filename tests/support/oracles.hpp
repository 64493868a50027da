// Independent oracles for the collision tests: linear programming (GLPK), the Minkowski difference's
// convex hull (Qhull, called directly), brute-force projection onto every face, and Bullet's 3D box-box.
// They share no code with the engine's collision detection (nothing from wedge/collision/ or any wedge
// header): points are dynamic Eigen vectors, so one oracle serves every dimension n = 2..6.
//
// Conventions:
//   * A polytope is the convex hull of its points (they need not all be extreme, they must span R^n).
//   * Half-spaces: x is inside facet f iff normal_f . x <= offset_f, normal_f of unit length, outward.
//   * The contact normal points from A to B: translating B by +depth * normal (or A by -depth * normal)
//     separates the two (to touching). For separated bodies depth = -distance and the normal is the
//     direction from A's closest point to B's closest point.
#pragma once

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

namespace wedge::oracle {

using Point = Eigen::VectorXd;
using Points = std::vector<Eigen::VectorXd>;

// Any fixed-size Eigen vectors (wedge::Vec<N>) as dynamic ones.
template <class V>
Points dynamic(const std::vector<V>& points) {
  Points out;
  out.reserve(points.size());
  for (const V& p : points) out.push_back(Point(p));
  return out;
}

// ---- (a) Linear programming: the L-infinity distance between two hulls ----------------------------

struct LpSeparation {
  // GLPK reached the optimum (glp_get_status == GLP_OPT). If false, nothing else is meaningful.
  bool optimal = false;
  std::string status;  // "optimal", or what went wrong
  // min t over lambda, mu >= 0, sum lambda = sum mu = 1, |sum lambda_i a_i - sum mu_j b_j|_inf <= t:
  // the L-infinity distance between conv(A) and conv(B), 0 when they intersect. Euclidean distance d
  // and this t satisfy t <= d <= sqrt(n) t.
  double distance = 0.0;
  Point point_a, point_b;  // the witnesses sum lambda_i a_i and sum mu_j b_j
  // GLPK's primal feasibility tolerance (tol_bnd) that succeeded: 1e-12, else 1e-10, else 1e-7.
  // Distances below it are not resolved (may come out as 0).
  double feasibility_tolerance = 0.0;
};

// Solved by GLPK's primal simplex (presolve off, terminal output off), with tol_bnd = 1e-12 first and
// looser ones only if that fails. Measured (coordinates of order 1): against the exact L-inf distance
// of 10,000 axis-aligned box pairs in 2D..6D at most 1.8e-13 off; for rotated boxes 2^-10 .. 2^-40
// apart in 3D..5D within the Euclidean bounds (t <= gap <= sqrt(n) t) for every gap >= 2^-28 = 3.7e-9;
// smaller gaps may come out as 0 (with a looser feasibility_tolerance). So "intersecting iff
// distance <= 1e-9" is right outside a band of 1e-8 around touching. (glp_exact was tried and
// dropped: Debian's GLPK returned answers up to 1.3e-10 off.)
LpSeparation lp_separation(const Points& a, const Points& b);

// ---- Qhull, called directly ------------------------------------------------------------------------

struct HullFacet {
  Point normal;               // unit, outward
  double offset = 0.0;        // normal . x <= offset inside
  std::vector<int> vertices;  // indices into the input points, sorted
};
struct Hull {
  int dim = 0;
  std::vector<HullFacet> facets;  // Qhull's default merging: coplanar points share one facet
  std::vector<int> vertices;      // indices of the extreme points, sorted
};
// Throws std::runtime_error if Qhull fails (flat or too few points).
Hull qhull(const Points& points);

// ---- (c) Closest point by brute force --------------------------------------------------------------

struct ClosestPoint {
  bool inside = false;  // p is in the polytope: max_f (normal_f . p - offset_f) <= 0
  // The closest point of the polytope to p, |p - point|, the dimension of the face whose relative
  // interior holds it (0 vertex, 1 edge, .., n-1 facet, n when p is inside) and that face's vertices
  // (input indices; all hull vertices when inside).
  Point point;
  double distance = 0.0;
  int face_dim = 0;
  std::vector<int> face;
  // For p inside: the distance to the boundary, min_f (offset_f - normal_f . p), the nearest boundary
  // point p + that * normal_f and that facet's normal. For p outside: 0, point and the unit vector from
  // point to p.
  double boundary_distance = 0.0;
  Point boundary_point;
  Point boundary_normal;
  int faces_tried = 0;  // how many faces were projected on (for cost reports)
};
// Projects p onto the affine hull of every face of every dimension that can hold the closest point
// (faces = the distinct nonempty intersections of Qhull facets' vertex sets, closed under intersection,
// plus the single vertices; for p outside, only faces within facets that p sees), keeps the
// projections that lie in the polytope (every facet inequality to 1e-9 x max(1, max |vertex|)) and
// returns the nearest. Exact up to that membership band and round-off.
ClosestPoint closest_point_brute_force(const Points& vertices, const Point& p);

// ---- (b) Minimum translation distance from the Minkowski difference -------------------------------

struct MinkowskiMtd {
  bool intersecting = false;  // the origin is in conv{a_i - b_j} (closed: touching counts)
  // > 0: penetration depth = min_f offset_f of the hull of A - B; < 0: minus the Euclidean distance.
  double depth = 0.0;
  Point normal;  // unit, from A to B (see the top of this file)
  // Intersecting: the outward normals of every facet of A - B with offset within tie_tolerance of the
  // minimum (concentric boxes tie on 2n facets), `normal` among them. Separated: just `normal`.
  std::vector<Point> tied_normals;
  int minkowski_facets = 0;
};
// The hull of {a_i - b_j} by Qhull. Origin inside: depth = min over facets of offset_f and normal =
// that facet's outward normal (moving B by depth * normal puts the origin on the boundary of A - B,
// i.e. the two touch). Outside: the closest point q of the hull to the origin by
// closest_point_brute_force; depth = -|q|, normal = -q / |q| (q = a - b for the closest pair).
MinkowskiMtd minkowski_mtd(const Points& a, const Points& b, double tie_tolerance = 1e-9);

// ---- (d) Bullet's 3D box-box -------------------------------------------------------------------------

struct BulletBoxBox {
  // btBoxBoxDetector (ODE's dBoxBox: separating axes over 3 + 3 face normals and 9 edge pairs, with a
  // 5% preference for face axes over edge-edge axes). Reports only overlapping boxes.
  bool intersecting = false;
  double depth = 0.0;                          // the deepest reported point's penetration (> 0)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, from A to B
  std::vector<Eigen::Vector3d> contact_points;       // up to 4, on B's surface as Bullet reports them
  std::vector<double> contact_depths;                // per point, > 0 penetrating
  std::vector<Eigen::Vector3d> contact_points_on_a;  // the partners on A: point + depth_i * normal
  // btGjkPairDetector with btGjkEpaPenetrationDepthSolver on the same boxes, collision margins 0:
  // signed distance (< 0 penetration depth) and its normal, from A to B. Separated, GJK is exact to
  // round-off (measured 3e-14 relative); overlapping, EPA is approximate (measured up to 2.5% off the
  // exact depth on axis-aligned boxes): use `depth` above for penetration.
  bool gjk_ok = false;
  double gjk_distance = 0.0;
  Eigen::Vector3d gjk_normal = Eigen::Vector3d::Zero();
};
// Boxes [-half, half] rotated by rot (3x3 rotation, x_world = pos + rot x_body) and moved to pos.
// Bullet is linked in double precision (bullet-float64), so nothing is rounded to float.
BulletBoxBox bullet_box_box(const Eigen::Vector3d& half_a, const Eigen::Vector3d& pos_a, const Eigen::Matrix3d& rot_a,
                            const Eigen::Vector3d& half_b, const Eigen::Vector3d& pos_b, const Eigen::Matrix3d& rot_b);

// ---- Support functions ------------------------------------------------------------------------------

// max_i a_i . u - min_j b_j . u: for a unit u, how far B must move along +u to separate from A (< 0:
// the gap along u). The minimum over all unit u is the penetration depth; any contact normal u that
// claims depth d can be checked against it: d >= this overlap means B moved by d u no longer overlaps.
double directional_overlap(const Points& a, const Points& b, const Point& u);

// ---- Helpers for random tests ------------------------------------------------------------------------

// The 2^n corners of the box [-half, half], rotated by rot (n x n) and moved to pos.
Points box_vertices(const Point& half, const Point& pos, const Eigen::MatrixXd& rot);
// A uniformly random rotation (Haar measure: QR of a Gaussian matrix with R's diagonal made positive,
// then one column negated if needed for det = +1).
Eigen::MatrixXd random_rotation(int n, std::mt19937_64& rng);
// `count` points uniform in the n-ball of the given radius around centre (count >= n + 1 spans R^n
// with probability 1).
Points random_points_in_ball(int n, int count, double radius, const Point& centre, std::mt19937_64& rng);

}  // namespace wedge::oracle
