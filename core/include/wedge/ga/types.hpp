// Value types of G(R^N): vectors, bivectors, rotors and general multivectors. Fixed size, no heap.
//
// Layouts (see blades.hpp for the orders):
//   Vec<N>          : (e0, .., e(N-1))                               N numbers, an Eigen column
//   Bivector<N>     : (e01, e02, .., e12, ..)                        k = N(N-1)/2 numbers
//   Rotor<N>        : (1, e01, .., e0123, .., e012345)               2^(N-1) numbers (8 in 4D)
//   Multivector<N>  : (1, e0, .., e01, .., e012, .., e0..(N-1))      2^N numbers
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "wedge/ga/blades.hpp"

namespace wedge {

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;
template <int N>
using Mat = Eigen::Matrix<double, N, N>;

// Number of bivector components (the dimension of the rotation group) for R^N.
template <int N>
inline constexpr int kBiv = N * (N - 1) / 2;
template <int N>
inline constexpr int kEven = 1 << (N - 1);

// k x k matrices on bivectors (inertia tensors, [R]_2) and the k x N matrix [r]_*.
template <int N>
using BivMat = Eigen::Matrix<double, kBiv<N>, kBiv<N>>;
template <int N>
using WedgeMat = Eigen::Matrix<double, kBiv<N>, N>;

// True when every coefficient is finite. Eigen's allFinite() computes x - x, which raises the invalid-
// operation exception for an infinity; this classifies each number (std::isfinite raises nothing), so a
// check for bad input stays quiet under floating-point traps (tests/main.cpp).
template <class Derived>
bool all_finite(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m.derived().coeff(i, j))) return false;
  return true;
}

namespace detail {
// A thin fixed-size coefficient array with arithmetic; Derived adds meaning.
template <class Derived, int Size>
struct Coeffs {
  using Array = Eigen::Matrix<double, Size, 1>;
  Array c = Array::Zero();

  static constexpr int size() { return Size; }
  double& operator[](int i) { return c[i]; }
  double operator[](int i) const { return c[i]; }
  const Array& coeffs() const { return c; }
  Array& coeffs() { return c; }

  static Derived zero() { return Derived{}; }
  static Derived from(const Array& a) {
    Derived d;
    d.c = a;
    return d;
  }
  Derived operator+(const Derived& o) const { return from(c + o.c); }
  Derived operator-(const Derived& o) const { return from(c - o.c); }
  Derived operator-() const { return from(-c); }
  Derived operator*(double s) const { return from(c * s); }
  Derived operator/(double s) const { return from(c / s); }
  friend Derived operator*(double s, const Derived& d) { return from(d.c * s); }
  Derived& operator+=(const Derived& o) {
    c += o.c;
    return static_cast<Derived&>(*this);
  }
  Derived& operator-=(const Derived& o) {
    c -= o.c;
    return static_cast<Derived&>(*this);
  }
  Derived& operator*=(double s) {
    c *= s;
    return static_cast<Derived&>(*this);
  }
  bool operator==(const Derived& o) const { return c == o.c; }
  // Euclidean norm of the coefficients; for a bivector |B|^2 = -<B B>_0.
  double norm() const { return c.norm(); }
  double squared_norm() const { return c.squaredNorm(); }
  bool all_finite() const { return wedge::all_finite(c); }
};
}  // namespace detail

template <int N>
struct Bivector : detail::Coeffs<Bivector<N>, kBiv<N>> {
  // Component of e_ij for i < j.
  static constexpr int index(int i, int j) {
    return ga::Blades<N>::template index<ga::Set::Bivector>()[(1u << i) | (1u << j)];
  }
  static Bivector basis(int i, int j) {
    Bivector b;
    b.c[index(i, j)] = 1.0;
    return b;
  }
  double operator()(int i, int j) const { return i < j ? this->c[index(i, j)] : -this->c[index(j, i)]; }
};

template <int N>
struct Rotor : detail::Coeffs<Rotor<N>, kEven<N>> {
  static Rotor identity() {
    Rotor r;
    r.c[0] = 1.0;
    return r;
  }
  double scalar() const { return this->c[0]; }
  // The bivector part, components 1..k.
  Bivector<N> bivector() const {
    Bivector<N> b;
    b.c = this->c.template segment<kBiv<N>>(1);
    return b;
  }
  static Rotor from_parts(double s, const Bivector<N>& b) {
    Rotor r;
    r.c[0] = s;
    r.c.template segment<kBiv<N>>(1) = b.c;
    return r;
  }
};

template <int N>
struct Multivector : detail::Coeffs<Multivector<N>, (1 << N)> {
  static Multivector scalar(double s) {
    Multivector m;
    m.c[0] = s;
    return m;
  }
  // Coefficient of the basis blade with bitmask `blade`.
  double blade(unsigned b) const { return this->c[ga::Blades<N>::template index<ga::Set::Full>()[b]]; }
  double& blade(unsigned b) { return this->c[ga::Blades<N>::template index<ga::Set::Full>()[b]]; }
};

}  // namespace wedge
