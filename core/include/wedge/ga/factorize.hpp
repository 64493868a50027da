// Rotor repair by factorisation into unit vectors (paper section 4, after Perwass 2009).
//
// In 4D and up, scaling a drifted rotor to unit norm is not enough: an even element with |R| = 1 need
// not satisfy R ~R = 1 (in 4D its grade-4 part can be non-zero), and then R x ~R is not a rotation.
// Instead, R is rebuilt as a product of unit vectors, which is always an exact rotor. Constructively
// (Cartan-Dieudonne): for i = 0..N-2, take b = the image of e_i under what is left of R, made orthogonal
// to e_0..e_(i-1) and unit; the simple rotor S_i = b m, m = unit(e_i + b), turns e_i onto b and fixes
// e_0..e_(i-1) (turns beyond 120 degrees go in two legs within the same plane); peel it off. What remains fixes N-1 axes, so it is +-1, and R = +-S_0 S_1 .. S_(N-2).
#pragma once

#include "wedge/ga/products.hpp"

namespace wedge {

// R ~= sign * v[0] v[1] .. v[count-1], every v a unit vector (2 or 4 per peeled axis).
template <int N>
struct RotorFactors {
  std::array<Vec<N>, 4 * (N - 1)> v{};
  int count = 0;
  double sign = 1.0;
};

namespace ga::detail {
// x -> u x u, the reflection through the line u (unit u): 2 (u.x) u - x.
template <int N>
Vec<N> line_reflect(const Vec<N>& u, const Vec<N>& x) {
  return (2.0 * u.dot(x)) * u - x;
}
}  // namespace ga::detail

// Factorises the rotation M (any N x N matrix close to a rotation with det > 0) into unit vectors.
template <int N>
RotorFactors<N> factorize_matrix(Mat<N> m) {
  using ga::detail::line_reflect;
  RotorFactors<N> f;
  for (int i = 0; i < N - 1; ++i) {
    Vec<N> b = m.col(i);
    for (int j = 0; j < i; ++j) b[j] = 0.0;  // orthogonal to the axes already fixed
    const double len = b.norm();
    if (!(len > 0.0)) continue;  // not a rotation; nothing sensible to peel
    b /= len;
    const Vec<N> a = Vec<N>::Unit(i);
    // Turn a onto b through the bisector (for b near -a in two legs, below).
    auto peel = [&](const Vec<N>& from, const Vec<N>& to) {
      const Vec<N> mid = (from + to).normalized();
      f.v[f.count++] = to;
      f.v[f.count++] = mid;
      // What is left is ~S M: apply x -> ~S x S = mid (to x to) mid to the remaining columns.
      for (int j = i; j < N; ++j) m.col(j) = line_reflect<N>(mid, line_reflect<N>(to, m.col(j)));
    };
    if (a.dot(b) > -0.5) {
      peel(a, b);
    } else {
      // Via c, the unit part of b orthogonal to a: both legs stay in the plane of a and b, so a rotation
      // confined to a subspace is factorised inside it. Only for b = -a (no plane) is an axis chosen.
      Vec<N> c = b - a.dot(b) * a;
      if (c.norm() > 1e-8) {
        c.normalize();
      } else {
        int k = i + 1;
        for (int j = i + 2; j < N; ++j)
          if (std::abs(b[j]) < std::abs(b[k])) k = j;
        c = Vec<N>::Unit(k);
      }
      peel(c, b);  // S(a->b) = S(c->b) S(a->c): the left factor is peeled first
      peel(a, c);
    }
  }
  return f;
}

// The product of the factors: an exact rotor up to round-off.
template <int N>
Rotor<N> compose(const RotorFactors<N>& f) {
  Rotor<N> r = Rotor<N>::identity() * f.sign;
  for (int i = 0; i + 1 < f.count; i += 2) {
    const Vec<N>& x = f.v[i];
    const Vec<N>& y = f.v[i + 1];
    // r (x y) with x y = x.y + x^y: a rotor times a scalar and a bivector (kBiv<N> terms per rotor
    // component, where a rotor product would take kEven<N>).
    Rotor<N> next = r * x.dot(y);
    ga::detail::product<ga::Terms<N, ga::Set::Even, ga::Set::Bivector, ga::Set::Even, ga::Product::Geometric>>(
        r, outer<N>(x, y), next);
    r = next;
  }
  return r;
}

// A rotor of a rotation matrix (R and -R are the same rotation; which one is returned is unspecified).
template <int N>
Rotor<N> rotor_from_matrix(const Mat<N>& m) {
  return compose(factorize_matrix<N>(m));
}

// Factorisation of a (possibly drifted) rotor, keeping its sign.
template <int N>
RotorFactors<N> factorize(const Rotor<N>& r) {
  RotorFactors<N> f = factorize_matrix<N>(to_matrix(r));
  if (compose(f).c.dot(r.c) < 0.0) f.sign = -1.0;
  return f;
}

// Repairs drift: the nearest exact rotor with the same sign (R ~R = 1 to round-off). (factorize's
// product, negated where the sign differs: negation is exact, so this is compose(factorize(r)) with
// one product of the factors instead of two.)
template <int N>
Rotor<N> repair(const Rotor<N>& r) {
  if constexpr (N <= 3) {
    return r / r.norm();  // for N <= 3 every unit even element is a rotor
  } else {
    const Rotor<N> out = compose(factorize_matrix<N>(to_matrix(r)));
    return out.c.dot(r.c) < 0.0 ? out * -1.0 : out;
  }
}

}  // namespace wedge
