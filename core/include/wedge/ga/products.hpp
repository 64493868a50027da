// Products of G(R^N) on the typed values of types.hpp.
//
// Every kernel is a compile-time list of terms out[o] += +-a[i]*b[j] (blades.hpp), unrolled by a fold
// expression, so each product is straight-line code with the exact term count of the algebra, e.g. 64
// multiplies for a 4D rotor composition. Terms are summed in table order: results are bit-reproducible.
// Sign conventions are the paper's: x' = R x ~R, dR/dt = -1/2 w R, point velocity r . w (left contraction).
#pragma once

#include <cstring>
#include <utility>

#include "wedge/ga/types.hpp"

namespace wedge {
namespace ga::detail {

// The coefficients of a value as a plain array: Eigen vectors, or the typed values' `c`.
template <class X>
inline auto coeff_data(X& x) {
  if constexpr (requires { x.c.data(); })
    return x.c.data();
  else
    return x.data();
}

// One expression per term on raw arrays: no template is instantiated and no overload resolved per term
// (the per-term function templates this replaced made GA-heavy files take minutes to compile). X is
// double, or a vector of doubles for the contact solver's lanes (one independent product per lane).
// (apply_terms_inline is forced inline, for the solver's lanes, whose values a call would pass through
// memory; the products below leave the choice to the compiler, which measured faster for them.)
template <const auto& T, class X, std::size_t... I>
[[gnu::always_inline]] inline void apply_terms_inline([[maybe_unused]] const X* __restrict a,
                                                      [[maybe_unused]] const X* __restrict b,
                                                      [[maybe_unused]] X* __restrict o, std::index_sequence<I...>) {
  constexpr const Term* t = T.data();  // built-in subscripts: std::array's operator[] is an overload set
  ((t[I].sign > 0 ? o[t[I].out] += a[t[I].a] * b[t[I].b] : o[t[I].out] -= a[t[I].a] * b[t[I].b]), ...);
}
template <const auto& T, class X, std::size_t... I>
inline void apply_terms(const X* __restrict a, const X* __restrict b, X* __restrict o, std::index_sequence<I...> i) {
  apply_terms_inline<T>(a, b, o, i);
}

// The number of coefficients of a value (Eigen vector or typed value).
template <class X>
constexpr int coeff_count() {
  if constexpr (requires { X::size(); })
    return X::size();
  else
    return X::SizeAtCompileTime;
}

// out[0..K) = t[0..K), two coefficients per 16-byte store. The callers' Eigen code reads results two at
// a time (SSE2 packets); a packet loaded from two separate 8-byte stores cannot be forwarded from the
// store buffer and waits until they reach the cache (~12 cycles, twice per point velocity in the solver
// passes). Pairing the values in registers first (unpcklpd) lets each load take its store's data.
template <int K>
inline void store_pairs(const double* t, double* out) {
  using Pair = double __attribute__((vector_size(16)));
  int i = 0;
  for (; i + 1 < K; i += 2) {
    const Pair x = {t[i], t[i + 1]};
    std::memcpy(out + i, &x, sizeof x);
  }
  if (i < K) out[i] = t[i];
}

// o = sum over the terms of table T (o must start at zero).
template <class Tm, class A, class B, class O>
inline void product(const A& a, const B& b, O& o) {
  ga::detail::apply_terms<Tm::table>(coeff_data(a), coeff_data(b), coeff_data(o),
                                     std::make_index_sequence<Tm::table.size()>{});
}
// The same, for results that Eigen code reads next: the sums run in locals the compiler keeps in
// registers and are then stored in pairs (store_pairs). The same arithmetic, in the same order.
template <class Tm, class A, class B, class O>
inline void product_paired(const A& a, const B& b, O& o) {
  constexpr int K = coeff_count<O>();
  double* out = coeff_data(o);
  double t[K];
  for (int i = 0; i < K; ++i) t[i] = out[i];
  ga::detail::apply_terms<Tm::table>(coeff_data(a), coeff_data(b), t, std::make_index_sequence<Tm::table.size()>{});
  store_pairs<K>(t, out);
}

// The same sum as a plain loop: for the general multivector products, which are not hot and whose
// 4096-term 6D tables would cost minutes of compile time if unrolled.
template <class Tm, class A, class B, class O>
inline void product_loop(const A& a, const B& b, O& o) {
  for (const Term& t : Tm::table) o[t.out] += t.sign * (a[t.a] * b[t.b]);
}

template <int N, Set S>
constexpr std::array<double, (1 << N)> reverse_signs() {
  constexpr auto ord = Blades<N>::template order<S>();
  std::array<double, (1 << N)> s{};
  for (int i = 0; i < int(ord.size()); ++i) s[i] = reverse_sign(grade_of(ord[i]));
  return s;
}

}  // namespace ga::detail

// ---------------------------------------------------------------- general multivectors
template <int N>
Multivector<N> operator*(const Multivector<N>& a, const Multivector<N>& b) {
  using namespace ga;
  Multivector<N> o;
  ga::detail::product_loop<Terms<N, Set::Full, Set::Full, Set::Full, Product::Geometric>>(a, b, o);
  return o;
}
template <int N>
Multivector<N> outer(const Multivector<N>& a, const Multivector<N>& b) {
  using namespace ga;
  Multivector<N> o;
  ga::detail::product_loop<Terms<N, Set::Full, Set::Full, Set::Full, Product::Outer>>(a, b, o);
  return o;
}
template <int N>
Multivector<N> left_contraction(const Multivector<N>& a, const Multivector<N>& b) {
  using namespace ga;
  Multivector<N> o;
  ga::detail::product_loop<Terms<N, Set::Full, Set::Full, Set::Full, Product::LeftContraction>>(a, b, o);
  return o;
}
template <int N>
Multivector<N> reverse(const Multivector<N>& a) {
  static constexpr auto s = ga::detail::reverse_signs<N, ga::Set::Full>();
  Multivector<N> o;
  for (int i = 0; i < (1 << N); ++i) o[i] = s[i] * a[i];
  return o;
}
// The grade-g part.
template <int N>
Multivector<N> grade(const Multivector<N>& a, int g) {
  static constexpr auto ord = ga::Blades<N>::template order<ga::Set::Full>();
  Multivector<N> o;
  for (int i = 0; i < (1 << N); ++i)
    if (ga::grade_of(ord[i]) == g) o[i] = a[i];
  return o;
}

// Embeddings into, and projections out of, the full algebra.
template <int N>
Multivector<N> to_multivector(const Vec<N>& v) {
  Multivector<N> m;
  m.c.template segment<N>(1) = v;
  return m;
}
template <int N>
Multivector<N> to_multivector(const Bivector<N>& b) {
  Multivector<N> m;
  m.c.template segment<kBiv<N>>(1 + N) = b.c;
  return m;
}
template <int N>
Multivector<N> to_multivector(const Rotor<N>& r) {
  static constexpr auto even = ga::Blades<N>::template order<ga::Set::Even>();
  static constexpr auto full = ga::Blades<N>::template index<ga::Set::Full>();
  Multivector<N> m;
  for (int i = 0; i < kEven<N>; ++i) m[full[even[i]]] = r[i];
  return m;
}
template <int N>
Vec<N> vector_part(const Multivector<N>& m) {
  return m.c.template segment<N>(1);
}
template <int N>
Bivector<N> bivector_part(const Multivector<N>& m) {
  return Bivector<N>::from(m.c.template segment<kBiv<N>>(1 + N));
}
template <int N>
Rotor<N> even_part(const Multivector<N>& m) {
  static constexpr auto even = ga::Blades<N>::template order<ga::Set::Even>();
  static constexpr auto full = ga::Blades<N>::template index<ga::Set::Full>();
  Rotor<N> r;
  for (int i = 0; i < kEven<N>; ++i) r[i] = m[full[even[i]]];
  return r;
}

// ---------------------------------------------------------------- vectors and bivectors
// a ^ b.
template <int N>
Bivector<N> outer(const Vec<N>& a, const Vec<N>& b) {
  using namespace ga;
  Bivector<N> o;
  ga::detail::product<Terms<N, Set::Vector, Set::Vector, Set::Bivector, Product::Outer>>(a, b, o);
  return o;
}
// r . w, the left contraction of a vector on a bivector: the velocity of point r under rotation w.
template <int N>
Vec<N> dot(const Vec<N>& r, const Bivector<N>& w) {
  using namespace ga;
  Vec<N> o = Vec<N>::Zero();
  ga::detail::product_paired<Terms<N, Set::Vector, Set::Bivector, Set::Vector, Product::LeftContraction>>(r, w, o);
  return o;
}
// The commutator product A x B = (AB - BA)/2; for bivectors it is again a bivector.
template <int N>
Bivector<N> commutator(const Bivector<N>& a, const Bivector<N>& b) {
  using namespace ga;
  Bivector<N> o;
  ga::detail::product<Terms<N, Set::Bivector, Set::Bivector, Set::Bivector, Product::Commutator>>(a, b, o);
  return o;
}
// The k x k matrix [a]x with [a]x b = a x b (commutator), for linearising gyroscopic terms.
template <int N>
BivMat<N> commutator_matrix(const Bivector<N>& a) {
  using namespace ga;
  BivMat<N> m = BivMat<N>::Zero();
  for (const Term& t : Terms<N, Set::Bivector, Set::Bivector, Set::Bivector, Product::Commutator>::table)
    m(t.out, t.b) += t.sign * a[t.a];
  return m;
}
// <A B>_0 = -sum A_ij B_ij: the scalar product of bivectors.
template <int N>
double scalar_product(const Bivector<N>& a, const Bivector<N>& b) {
  return -a.c.dot(b.c);
}

// ---------------------------------------------------------------- rotors
template <int N>
Rotor<N> operator*(const Rotor<N>& a, const Rotor<N>& b) {
  using namespace ga;
  Rotor<N> o;
  ga::detail::product<Terms<N, Set::Even, Set::Even, Set::Even, Product::Geometric>>(a, b, o);
  return o;
}
template <int N>
Rotor<N> reverse(const Rotor<N>& a) {
  static constexpr auto s = ga::detail::reverse_signs<N, ga::Set::Even>();
  Rotor<N> o;
  for (int i = 0; i < kEven<N>; ++i) o[i] = s[i] * a[i];
  return o;
}
// A bivector as a rotor-shaped even element (scalar and grade >= 4 parts zero).
template <int N>
Rotor<N> to_even(const Bivector<N>& b) {
  return Rotor<N>::from_parts(0.0, b);
}
// The sandwich R x ~R for a vector x: R x (an odd element), then times ~R. For a unit rotor the result
// is a pure, equally long vector. Expanded, it is the rotation matrix of R (to_matrix) applied to x; in
// 3D, R = s + b01 e01 + b02 e02 + b12 e12:
//   x'0 = (s² - b01² - b02² + b12²) x0 + 2 (s b01 - b02 b12) x1 + 2 (s b02 + b01 b12) x2
//   x'1 = -2 (s b01 + b02 b12) x0 + (s² - b01² + b02² - b12²) x1 + 2 (s b12 - b01 b02) x2
//   x'2 = 2 (b01 b12 - s b02) x0 - 2 (s b12 + b01 b02) x1 + (s² + b01² - b02² - b12²) x2
// and in 4D, R = s + b01 e01 + b02 e02 + b03 e03 + b12 e12 + b13 e13 + b23 e23 + p e0123:
//   x'0 = (s² - p² - b01² - b02² - b03² + b12² + b13² + b23²) x0 + 2 (s b01 + p b23 - b02 b12 - b03 b13) x1
//         + 2 (s b02 - p b13 + b01 b12 - b03 b23) x2 + 2 (s b03 + p b12 + b01 b13 + b02 b23) x3
//   x'1 = -2 (s b01 + p b23 + b02 b12 + b03 b13) x0 + (s² - p² - b01² + b02² + b03² - b12² - b13² + b23²) x1
//         + 2 (s b12 + p b03 - b01 b02 - b13 b23) x2 + 2 (s b13 - p b02 - b01 b03 + b12 b23) x3
//   x'2 = 2 (p b13 - s b02 + b01 b12 - b03 b23) x0 - 2 (s b12 + p b03 + b01 b02 + b13 b23) x1
//         + (s² - p² + b01² - b02² + b03² - b12² + b13² - b23²) x2 + 2 (s b23 + p b01 - b02 b03 - b12 b13) x3
//   x'3 = 2 (b01 b13 + b02 b23 - s b03 - p b12) x0 + 2 (p b02 - s b13 - b01 b03 + b12 b23) x1
//         - 2 (s b23 + p b01 + b02 b03 + b12 b13) x2 + (s² - p² + b01² + b02² - b03² + b12² - b13² - b23²) x3
// (a unit rotor has s² + |B|² + p² = 1; tests/core/ga/test_products.cpp checks these against the kernel). The
// code forms the two products term by term (blades.hpp): one kernel for every N.
template <int N>
Vec<N> rotate(const Rotor<N>& r, const Vec<N>& x) {
  using namespace ga;
  Eigen::Matrix<double, kEven<N>, 1> rx = Eigen::Matrix<double, kEven<N>, 1>::Zero();  // odd: R x
  ga::detail::product<Terms<N, Set::Even, Set::Vector, Set::Odd, Product::Geometric>>(r, x, rx);
  const Rotor<N> rr = reverse(r);
  Vec<N> o = Vec<N>::Zero();
  ga::detail::product<Terms<N, Set::Odd, Set::Even, Set::Vector, Product::Geometric>>(rx, rr, o);
  return o;
}
// The sandwich R B ~R for a bivector B.
template <int N>
Bivector<N> rotate(const Rotor<N>& r, const Bivector<N>& b) {
  using namespace ga;
  Rotor<N> rb;
  ga::detail::product<Terms<N, Set::Even, Set::Bivector, Set::Even, Product::Geometric>>(r, b, rb);
  const Rotor<N> rr = reverse(r);
  Bivector<N> o;
  ga::detail::product<Terms<N, Set::Even, Set::Even, Set::Bivector, Product::Geometric>>(rb, rr, o);
  return o;
}
// ~R x R: from world into the body frame.
template <int N>
Vec<N> rotate_inverse(const Rotor<N>& r, const Vec<N>& x) {
  return rotate(reverse(r), x);
}
template <int N>
Bivector<N> rotate_inverse(const Rotor<N>& r, const Bivector<N>& b) {
  return rotate(reverse(r), b);
}

// ---------------------------------------------------------------- matrix forms
// The N x N rotation matrix of R: column j is R e_j ~R, evaluated as the compile-time quadratic form of
// blades.hpp (SandwichMatrixTerms). Unrolled up to 4D; a plain loop beyond, to keep compile times short.
template <int N>
Mat<N> to_matrix(const Rotor<N>& r) {
  using T = ga::SandwichMatrixTerms<N>;
  Mat<N> m = Mat<N>::Zero();
  if constexpr (N <= 4) {
    const double* rc = r.c.data();
    double* mc = m.data();  // column-major
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      constexpr const ga::QuadTerm* t = T::table.data();
      ((mc[t[I].j * N + t[I].i] += double(t[I].coef) * (rc[t[I].a] * rc[t[I].b])), ...);
    }(std::make_index_sequence<T::table.size()>{});
  } else {
    for (const ga::QuadTerm& t : T::table) m(t.i, t.j) += double(t.coef) * (r[t.a] * r[t.b]);
  }
  return m;
}

// [R]_2: the k x k matrix with [R]_2 B = R B ~R, the second compound of the rotation matrix M:
// column (ij) is (M e_i) ^ (M e_j).
template <int N>
BivMat<N> bivector_matrix(const Mat<N>& m) {
  static constexpr auto ord = ga::Blades<N>::template order<ga::Set::Bivector>();
  BivMat<N> out;
  for (int col = 0; col < kBiv<N>; ++col) {
    const int i = std::countr_zero(ord[col]), j = 31 - std::countl_zero(ord[col]);
    for (int row = 0; row < kBiv<N>; ++row) {
      const int a = std::countr_zero(ord[row]), b = 31 - std::countl_zero(ord[row]);
      out(row, col) = m(a, i) * m(b, j) - m(b, i) * m(a, j);
    }
  }
  return out;
}
template <int N>
BivMat<N> bivector_matrix(const Rotor<N>& r) {
  return bivector_matrix<N>(to_matrix(r));
}

// [r]_*: the k x N matrix with r ^ a = [r]_* a, and r . w = [r]_*^T w (paper eq. 3).
template <int N>
WedgeMat<N> wedge_matrix(const Vec<N>& r) {
  static constexpr auto ord = ga::Blades<N>::template order<ga::Set::Bivector>();
  WedgeMat<N> m = WedgeMat<N>::Zero();
  for (int row = 0; row < kBiv<N>; ++row) {
    const int i = std::countr_zero(ord[row]), j = 31 - std::countl_zero(ord[row]);
    // (r ^ a)_ij = r_i a_j - r_j a_i
    m(row, j) = r[i];
    m(row, i) = -r[j];
  }
  return m;
}

// The skew N x N matrix W with W x = x . w: the generator of the rotation of bivector w.
template <int N>
Mat<N> generator_matrix(const Bivector<N>& w) {
  Mat<N> m = Mat<N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      // e_i . e_ij = e_j and e_j . e_ij = -e_i
      const double v = w[Bivector<N>::index(i, j)];
      m(j, i) = v;
      m(i, j) = -v;
    }
  return m;
}
// The bivector of a skew matrix (inverse of generator_matrix; the symmetric part is ignored).
template <int N>
Bivector<N> bivector_from_generator(const Mat<N>& m) {
  Bivector<N> w;
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) w[Bivector<N>::index(i, j)] = 0.5 * (m(j, i) - m(i, j));
  return w;
}

}  // namespace wedge
