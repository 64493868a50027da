// Basis blades of the Euclidean geometric algebra G(R^N), as compile-time tables.
//
// A blade is a bitmask: bit i set <=> e_i is a factor (e_0 is bit 0). Storage orders, the paper's
// convention, used by every file format and tool of the project:
//   full multivector  : grade ascending, lexicographic within a grade (1, e0, e1, .., e01, e02, .., e12, ..)
//   even (rotor)      : scalar, then grade 2, grade 4, .. each lexicographic (8 numbers in 4D)
//   odd               : grade 1, grade 3, .. each lexicographic
//   bivector          : e01, e02, .., e0(n-1), e12, .. (k = n(n-1)/2 numbers)
// Products are expanded at compile time into lists of Terms (out += sign * a[ia] * b[ib]) that the
// kernels in products.hpp unroll; the slow bitmask reference in tests/support checks every one.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace wedge::ga {

constexpr int binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  int r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

constexpr int grade_of(unsigned blade) { return std::popcount(blade); }

// Sign of e_a e_b for basis blades a, b (Euclidean metric, e_i^2 = +1): the parity of the number of
// transpositions needed to bring the concatenated factors into ascending order.
constexpr int blade_product_sign(unsigned a, unsigned b) {
  int swaps = 0;
  for (a >>= 1; a != 0; a >>= 1) swaps += std::popcount(a & b);
  return (swaps & 1) ? -1 : 1;
}

// Reverse of a grade-g blade: (-1)^(g(g-1)/2).
constexpr int reverse_sign(int grade) { return ((grade * (grade - 1) / 2) & 1) ? -1 : 1; }

// Lexicographic comparison of two blades of equal grade by their ascending index lists.
constexpr bool lex_less(unsigned a, unsigned b) {
  while (a != 0 && b != 0) {
    const unsigned la = a & (~a + 1u), lb = b & (~b + 1u);  // lowest set bits
    if (la != lb) return la < lb;
    a ^= la;
    b ^= lb;
  }
  return false;
}

enum class Set { Full, Even, Odd, Vector, Bivector, Quadvector, Pseudoscalar };

template <int N>
struct Blades {
  static_assert(N >= 2 && N <= 6, "Wedge supports dimensions 2..6");
  static constexpr int kFull = 1 << N;
  static constexpr int kEven = 1 << (N - 1);
  static constexpr int kBiv = N * (N - 1) / 2;

  static constexpr bool in_set(Set s, unsigned blade) {
    const int g = grade_of(blade);
    switch (s) {
      case Set::Full: return true;
      case Set::Even: return g % 2 == 0;
      case Set::Odd: return g % 2 == 1;
      case Set::Vector: return g == 1;
      case Set::Bivector: return g == 2;
      case Set::Quadvector: return g == 4;
      case Set::Pseudoscalar: return g == N;
    }
    return false;
  }
  static constexpr int size(Set s) {
    int n = 0;
    for (unsigned m = 0; m < unsigned(kFull); ++m) n += in_set(s, m) ? 1 : 0;
    return n;
  }
  // Position -> bitmask for the storage order of set s.
  template <Set S>
  static constexpr std::array<unsigned, size(S)> order() {
    std::array<unsigned, size(S)> out{};
    int n = 0;
    for (int g = 0; g <= N; ++g) {
      const int first = n;
      for (unsigned m = 0; m < unsigned(kFull); ++m)
        if (grade_of(m) == g && in_set(S, m)) out[n++] = m;
      std::sort(out.begin() + first, out.begin() + n, lex_less);
    }
    return out;
  }
  // Bitmask -> position in set s, or -1.
  template <Set S>
  static constexpr std::array<int, kFull> index() {
    std::array<int, kFull> idx{};
    idx.fill(-1);
    constexpr auto ord = order<S>();
    for (int i = 0; i < int(ord.size()); ++i) idx[ord[i]] = i;
    return idx;
  }
};

// Which pairs of blades a product keeps.
enum class Product { Geometric, Outer, LeftContraction, Commutator };

constexpr bool keeps(Product p, unsigned a, unsigned b) {
  switch (p) {
    case Product::Geometric: return true;
    case Product::Outer: return (a & b) == 0;
    case Product::LeftContraction: return (a & b) == a;  // grade(ab) = grade(b) - grade(a)
    case Product::Commutator:  // (AB - BA)/2 survives only where e_a e_b anticommute
      return blade_product_sign(a, b) != blade_product_sign(b, a);
  }
  return false;
}

struct Term {
  std::uint16_t a, b, out;
  std::int8_t sign;
};

// All terms of (A op B) restricted to output set O, for inputs from sets A and B.
template <int N, Set A, Set B, Set O, Product P>
struct Terms {
  using Bl = Blades<N>;
  static constexpr int count() {
    constexpr auto oa = Bl::template order<A>();
    constexpr auto ob = Bl::template order<B>();
    int n = 0;
    for (unsigned x : oa)
      for (unsigned y : ob)
        if (keeps(P, x, y) && Bl::in_set(O, x ^ y)) ++n;
    return n;
  }
  static constexpr std::array<Term, count()> make() {
    constexpr auto oa = Bl::template order<A>();
    constexpr auto ob = Bl::template order<B>();
    constexpr auto io = Bl::template index<O>();
    std::array<Term, count()> t{};
    int n = 0;
    for (int i = 0; i < int(oa.size()); ++i)
      for (int j = 0; j < int(ob.size()); ++j) {
        const unsigned x = oa[i], y = ob[j];
        if (!(keeps(P, x, y) && Bl::in_set(O, x ^ y))) continue;
        t[n++] = Term{std::uint16_t(i), std::uint16_t(j), std::uint16_t(io[x ^ y]),
                      std::int8_t(blade_product_sign(x, y))};
      }
    return t;
  }
  static constexpr auto table = make();
};

// The rotation matrix of a rotor as a quadratic form: M(i, j) = <R e_j ~R>_i = sum coef * R_a R_b over
// pairs a <= b of even blades. Derived at compile time from the blade products, so to_matrix costs one
// multiply-add per term instead of N sandwiches.
struct QuadTerm {
  std::uint16_t a, b, i, j;
  std::int8_t coef;
};

template <int N>
struct SandwichMatrixTerms {
  using Bl = Blades<N>;
  static constexpr int kE = Bl::kEven;
  // The even blades in rotor order and their positions, computed once (not in each call of the helpers
  // below: compilers that do not memoise constant evaluation would sort them for every coefficient).
  static constexpr auto even = Bl::template order<Set::Even>();
  static constexpr auto even_index = Bl::template index<Set::Even>();
  // <e_a e_j ~e_b>_i is a vector only when e_b = e_a e_j e_i up to sign: for each (i, j, a) one partner b.
  static constexpr int partner(int i, int j, int a) { return even_index[even[a] ^ (1u << j) ^ (1u << i)]; }
  // The coefficient of R_a R_b in M(i, j) for the ordered pair (a, b) = (a, partner(i, j, a)).
  static constexpr int raw(int i, int j, int a) {
    const unsigned ea = even[a], eb = even[partner(i, j, a)], m1 = ea ^ (1u << j);
    return blade_product_sign(ea, 1u << j) * blade_product_sign(m1, eb) * reverse_sign(grade_of(eb));
  }
  // coef(i, j, a, b) folded onto a <= b: the pair arises once from a and once from b = partner(a).
  static constexpr int folded(int i, int j, int a) {
    const int b = partner(i, j, a);
    return a == b ? raw(i, j, a) : raw(i, j, a) + raw(i, j, b);
  }
  static constexpr int count() {
    int n = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        for (int a = 0; a < kE; ++a) n += partner(i, j, a) >= a && folded(i, j, a) != 0 ? 1 : 0;
    return n;
  }
  // Terms ordered by column j, row i, then a (each a has one b), as the sums in to_matrix run.
  static constexpr std::array<QuadTerm, count()> make() {
    std::array<QuadTerm, count()> t{};
    int n = 0;
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        for (int a = 0; a < kE; ++a) {
          const int b = partner(i, j, a);
          if (b < a) continue;
          if (const int c = folded(i, j, a); c != 0)
            t[n++] = QuadTerm{std::uint16_t(a), std::uint16_t(b), std::uint16_t(i), std::uint16_t(j),
                              std::int8_t(c)};
        }
    return t;
  }
  static constexpr auto table = make();
};

}  // namespace wedge::ga
