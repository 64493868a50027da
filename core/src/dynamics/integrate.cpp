// Body integration (internal): the velocity half of a step (gravity, forces, torques, the gyroscopic
// term, drag) and gyroscopic_step, the implicit solve of the torque-free Euler equation.
#include "dynamics/integrate.hpp"

#include <cmath>

#include "linalg/fixed_size.hpp"
#include "linalg/isotropic.hpp"
#include "wedge/dimensions.hpp"

namespace wedge {

namespace {
// J = I - s ([m]x I - [I m]x), term by term from the commutator's table (out[o] += sign a[i] b[j]):
// ([m]x I)(o, :) = sum of sign m[i] I(j, :) over the terms of row o, and [I m]x has sign (I m)[i] at
// (o, j). About 2 (N - 2) terms per row instead of a dense k x k x k product.
template <int N>
BivMat<N> gyroscopic_jacobian(const BivMat<N>& inertia, const Bivector<N>& m, const Bivector<N>& im, double s) {
  BivMat<N> jac = inertia;
  for (const ga::Term& t : ga::Terms<N, ga::Set::Bivector, ga::Set::Bivector, ga::Set::Bivector,
                                     ga::Product::Commutator>::table) {
    const double f = s * t.sign;
    jac.row(t.out) -= (f * m[t.a]) * inertia.row(t.b);
    jac(t.out, t.b) += f * im[t.a];
  }
  return jac;
}

// The implicit midpoint equation I (w' - w) = h m x I m, m = (w + w') / 2, for a diagonal inertia, solved by
// fixed-point iteration w' <- w + h I^-1 (m x I m) from w' = w. The map's Jacobian is
// (h / 2) I^-1 ([m]x I - [I m]x), whose entry for the commutator term e_a x e_b -> e_o is +-(h / 2) m_a
// (I_b - I_a) / I_o. A rigid body's moments are I_pq = c_p + c_q (c the covariance's principal values), and
// a = pr, b = rq, o = pq give |I_b - I_a| / I_o = |c_q - c_p| / (c_p + c_q) <= 1 (3D's |I2 - I3| <= I1): the
// iteration contracts by about h |w| whatever the ratio of the moments, and a sub-step's h |w| ~ 0.01 reaches
// round-off in about 8 iterations of one commutator each. False if it has not after 24 (a large h |w|, or
// a diagonal that no body has): the caller then takes Newton's method.
template <int N>
bool midpoint_by_iteration(const Bivector<N>& inertia, const Bivector<N>& w, double h, Bivector<N>& out) {
  const Eigen::Array<double, kBiv<N>, 1> step = h / inertia.c.array();
  const double tolerance = 4e-16 * w.c.cwiseAbs().maxCoeff();
  Bivector<N> w2 = w;
  for (int iteration = 0; iteration < 24; ++iteration) {
    const Bivector<N> m = (w + w2) * 0.5;
    const Bivector<N> im = Bivector<N>::from((inertia.c.array() * m.c.array()).matrix());
    Bivector<N> next = w;
    next.c.array() += step * commutator(m, im).c.array();
    const bool converged = (next.c - w2.c).cwiseAbs().maxCoeff() <= tolerance;
    w2 = next;
    if (converged) {
      out = w2;
      return true;
    }
  }
  return false;
}

template <int N>
bool is_diagonal(const BivMat<N>& m) {
  for (int j = 0; j < kBiv<N>; ++j)
    for (int i = 0; i < kBiv<N>; ++i)
      if (i != j && m(i, j) != 0.0) return false;
  return true;
}

// The simplified Newton iterations of world.hpp's gyroscopic_step, for any inertia.
template <int N>
Bivector<N> gyroscopic_by_newton(const BivMat<N>& inertia, const Bivector<N>& w, double h, GyroscopicMethod method) {
  const bool euler = method == GyroscopicMethod::ImplicitEuler;
  const double t = euler ? 1.0 : 0.5;
  // Both iterations use the Jacobian at the first iterate w' = w (simplified Newton): it changes by
  // O(h |w|^2) over the step, so the second iteration still converges, at a cost of one factorisation.
  const Bivector<N> iw = Bivector<N>::from(inertia * w.c);
  const linalg::LuFactors<kBiv<N>> jac(gyroscopic_jacobian<N>(inertia, w, iw, t * h));
  // First iteration, from w' = w: I (w' - w) = 0 and m = w, so g = -h w x I w. Implicit Euler stops here.
  Bivector<N> w2 = w - Bivector<N>::from(jac.solve((commutator(w, iw) * -h).c));
  if (!euler) {
    const Bivector<N> m = (w + w2) * 0.5;
    const Bivector<N> im = Bivector<N>::from(inertia * m.c);
    const Bivector<N> g = Bivector<N>::from(inertia * (w2 - w).c) - commutator(m, im) * h;
    w2 -= Bivector<N>::from(jac.solve(g.c));
    const double e0 = w.c.dot(iw.c), e1 = w2.c.dot(inertia * w2.c);
    if (e1 > e0) w2 *= std::sqrt(e0 / e1);
  }
  return w2;
}

// The midpoint step of a diagonal inertia with these moments (inertia the same, for Newton's fallback).
template <int N>
Bivector<N> gyroscopic_diagonal(const Bivector<N>& moments, const BivMat<N>& inertia, const Bivector<N>& w, double h) {
  Bivector<N> w2;
  if (!midpoint_by_iteration<N>(moments, w, h, w2))
    return gyroscopic_by_newton<N>(inertia, w, h, GyroscopicMethod::ImplicitMidpoint);
  // (the converged midpoint conserves w . I w; round-off may still raise it by an ulp)
  const double e0 = w.c.dot(moments.c.cwiseProduct(w.c)), e1 = w2.c.dot(moments.c.cwiseProduct(w2.c));
  if (e1 > e0) w2 *= std::sqrt(e0 / e1);
  return w2;
}
}  // namespace

template <int N>
Bivector<N> gyroscopic_step(const BivMat<N>& inertia, const Bivector<N>& w, double h, GyroscopicMethod method) {
  if (method == GyroscopicMethod::ImplicitMidpoint && is_diagonal<N>(inertia))
    return gyroscopic_diagonal<N>(Bivector<N>::from(inertia.diagonal()), inertia, w, h);
  return gyroscopic_by_newton<N>(inertia, w, h, method);
}

namespace dynamics {

template <int N>
AngularModel<N> angular_model(const Body<N>& b, const Motion<N>& motion) {
  AngularModel<N> m;
  m.torque = !b.torque.c.isZero(0.0);
  m.body_frame = m.torque || (motion.gyroscopic && !linalg::is_isotropic(b.inertia));
  m.gyroscopic = motion.gyroscopic;
  m.diagonal = m.body_frame && m.gyroscopic && motion.gyroscopic_method == GyroscopicMethod::ImplicitMidpoint &&
               is_diagonal<N>(b.inertia);
  if (m.diagonal) m.moments = Bivector<N>::from(b.inertia.diagonal());
  return m;
}

template <int N>
void integrate_velocity(const Body<N>& b, const Motion<N>& motion, double h, Vec<N>& v, Bivector<N>& w) {
  integrate_velocity(b, angular_model(b, motion), motion, h, v, w);
}

template <int N>
void integrate_velocity(const Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h, Vec<N>& v,
                        Bivector<N>& w) {
  v += h * (motion.gravity + b.force * b.inv_mass);
  if (model.body_frame) {
    Bivector<N> wb = rotate_inverse(b.rotor, w);
    integrate_body_frame(b, model, motion, h, wb);
    w = rotate(b.rotor, wb);
  }
  v *= 1.0 / (1.0 + h * b.linear_drag);
  w *= 1.0 / (1.0 + h * b.angular_drag);
}

template <int N>
void integrate_body_frame(const Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h,
                          Bivector<N>& wb) {
  if (model.torque) wb.c += h * (b.inv_inertia * rotate_inverse(b.rotor, b.torque).c);
  if (model.diagonal)
    wb = gyroscopic_diagonal<N>(model.moments, b.inertia, wb, h);
  else if (model.gyroscopic)
    wb = gyroscopic_by_newton<N>(b.inertia, wb, h, motion.gyroscopic_method);
}

template <int N>
void advance_alone(Body<N>& b, const AngularModel<N>& model, const Motion<N>& motion, double h, int substeps,
                   bool repair_at_end, Vec<N>& v, Bivector<N>& w) {
  const Vec<N> dv = h * (motion.gravity + b.force * b.inv_mass);
  const double decay_v = 1.0 / (1.0 + h * b.linear_drag), decay_w = 1.0 / (1.0 + h * b.angular_drag);
  if (model.body_frame) {
    Bivector<N> wb = rotate_inverse(b.rotor, w);
    for (int k = 0; k < substeps; ++k) {
      v = (v + dv) * decay_v;
      integrate_body_frame(b, model, motion, h, wb);
      wb *= decay_w;
      b.center += h * v;
      b.rotor = b.rotor * exp<N>(wb * (-0.5 * h));
    }
    if (repair_at_end) b.rotor = repair(b.rotor);
    w = rotate(b.rotor, wb);
    return;
  }
  Bivector<N> turned{};  // w_1 + ... + w_n
  for (int k = 0; k < substeps; ++k) {
    v = (v + dv) * decay_v;
    w *= decay_w;
    turned += w;
    b.center += h * v;
  }
  b.rotor = exp<N>(turned * (-0.5 * h)) * b.rotor;
  if (repair_at_end) b.rotor = repair(b.rotor);
}

}  // namespace dynamics

#define WEDGE_INSTANTIATE(N)                                                                                 \
  template Bivector<N> gyroscopic_step<N>(const BivMat<N>&, const Bivector<N>&, double, GyroscopicMethod); \
  template void dynamics::integrate_velocity<N>(const Body<N>&, const dynamics::Motion<N>&, double, Vec<N>&, \
                                                Bivector<N>&);                                                \
  template dynamics::AngularModel<N> dynamics::angular_model<N>(const Body<N>&, const dynamics::Motion<N>&); \
  template void dynamics::advance_alone<N>(Body<N>&, const dynamics::AngularModel<N>&, const dynamics::Motion<N>&, \
                                           double, int, bool, Vec<N>&, Bivector<N>&);                              \
  template void dynamics::integrate_velocity<N>(const Body<N>&, const dynamics::AngularModel<N>&,             \
                                                const dynamics::Motion<N>&, double, Vec<N>&, Bivector<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
