// Mass, centre of mass, covariance and the k x k bivector inertia tensor of n-D solids: closed forms for
// boxes, balls and round products, and the covariance method of the paper's section 5 for simplicial
// meshes and polytopes; plus the principal frame in which both covariance and inertia are diagonal.
#pragma once

#include "wedge/body.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/types.hpp"
#include "wedge/mesh.hpp"
#include "wedge/shape.hpp"

namespace wedge {

template <int N>
struct MassProperties {
  double volume = 0.0;
  double mass = 0.0;
  Vec<N> center = Vec<N>::Zero();
  // integral of (x - c)(x - c)^T dm about the centre c, in the shape's own axes.
  Mat<N> covariance = Mat<N>::Zero();
  // integral of [r]_* [r]_*^T dm, r = x - c (paper section 4), in the shape's own axes; bivector order
  // e01, e02, .., e12, .. (types.hpp).
  BivMat<N> inertia = BivMat<N>::Zero();
};

// sum_ij C_ij [e_i]_* [e_j]_*^T (paper section 5): the inertia tensor of a body with covariance C. For a
// point mass at r (C = r r^T) it is the paper's Delta I = [r]_* [r]_*^T of appendix A. Entry (ab, ab)
// is C_aa + C_bb.
template <int N>
BivMat<N> inertia_from_covariance(const Mat<N>& covariance);

// Closed forms, centred at the origin. Throw wedge::Error for non-positive or non-finite sizes/density.
//   box, sides a = 2h:   V = prod a_i, covariance diag(m a_i^2 / 12), I_(ij) = m (a_i^2 + a_j^2) / 12
//   ball of radius r:    V = pi^(n/2) r^n / Gamma(n/2 + 1), covariance m r^2/(n+2) I, I_(ij) = 2 m r^2/(n+2)
//   round product:       V = product of factor volumes; per axis m r^2/(d+2) in a d-ball factor,
//                        m L^2/12 along an interval of length L = 2 half_length
template <int N>
MassProperties<N> box_mass_properties(const Vec<N>& half_extents, double density);
template <int N>
MassProperties<N> ball_mass_properties(double radius, double density);
template <int N>
MassProperties<N> round_product_mass_properties(const std::vector<ProductFactor>& factors, double density);

// Volume of the d-ball of radius r.
double ball_volume(int d, double radius);

// The covariance method of section 5 on a closed outward mesh (validated first): every cell spans a
// simplex with a reference point p (the mean of the used vertices); the simplex with edge matrix M
// has volume det(M)/N!, first moment det(M)/N! (p + sum of columns / (N+1)) and second moment about p
// det(M) M C M^T with the canonical C_xx = 2/(N+2)!, C_xy = 1/(N+2)!; the sums are then moved to the
// centre of mass.
template <int N>
MassProperties<N> mass_properties(const SimplexMesh<N>& mesh, double density);

// Dispatch on the shape: closed forms for box, ball and round products, the covariance method on the
// hull of a polytope and on a mesh. A half-space has no finite mass: wedge::Error.
template <int N>
MassProperties<N> mass_properties(const Shape<N>& shape, double density);

// The same properties rescaled to a given total mass (> 0): a density of mass / volume.
template <int N>
MassProperties<N> with_mass(const MassProperties<N>& props, double mass);

// The inertia tensor about another point p: I_c + m [d]_* [d]_*^T with d = c - p (parallel axes).
template <int N>
BivMat<N> inertia_about(const MassProperties<N>& props, const Vec<N>& point);

template <int N>
struct PrincipalFrame {
  // Columns are the principal axes (unit, det = +1): body = axes^T (world - center), world = center +
  // axes body. The covariance in this frame is diagonal, and so is the inertia.
  Mat<N> axes = Mat<N>::Identity();
  Vec<N> center = Vec<N>::Zero();
  // diag of axes^T covariance axes.
  Vec<N> covariance = Vec<N>::Zero();
  // [Q]_2^T I [Q]_2 with Q = axes: diagonal (off-diagonal round-off below 1e-9 of the largest entry
  // is checked and set to exactly zero).
  BivMat<N> inertia = BivMat<N>::Zero();
};

// Diagonalises the covariance (the axes are the identity if it is diagonal already, otherwise sorted by
// increasing variance, each axis' largest component made positive, then det fixed to +1).
template <int N>
PrincipalFrame<N> principal_frame(const MassProperties<N>& props);

// A dynamic body of the given shape and density (kg/m^n) at the origin: mass, centre of mass and inertia
// from mass_properties(). Throws wedge::Error for a half-space (use a static body without mass).
template <int N>
BodyDef<N> body_def(std::shared_ptr<const Shape<N>> shape, double density) {
  if (!shape) throw Error("body_def: no shape");
  const MassProperties<N> props = mass_properties(*shape, density);
  BodyDef<N> def;
  def.mass = props.mass;
  def.local_center = props.center;
  def.inertia = props.inertia;
  def.shape = std::move(shape);
  return def;
}

}  // namespace wedge
