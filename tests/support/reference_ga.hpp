// A slow, deliberately naive reference geometric algebra of Euclidean R^n (runtime n), used only by
// the tests to check the fast compile-time products of core/include/wedge/ga.
//
// It is written independently of core/: it includes no wedge header, shares no table, and derives
// every sign and every storage order on its own, in the most obvious way rather than the fastest:
//   * a basis blade is a bitmask (bit i <=> factor e_i); a multivector is a dense vector of 2^n
//     coefficients indexed by that bitmask (NOT by any storage order);
//   * e_A e_B is computed by writing out the factor list of A followed by that of B, bubble-sorting it
//     while counting the transpositions (each one flips the sign), then deleting equal adjacent pairs
//     (e_i e_i = +1, Euclidean metric);
//   * the outer product and the left contraction are the textbook grade projections of the geometric
//     product of blades: A_r ^ B_s = <A_r B_s>_{r+s}, and A_r _| B_s = <A_r B_s>_{s-r} (0 if r > s);
//   * the reverse of a blade reverses its factor list and re-sorts it, counting transpositions;
//   * the storage orders are built by listing the index tuples of each grade and sorting them with
//     std::vector's own lexicographic operator<.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace refga {

// The factor indices of a blade, ascending: 0b1011 -> {0, 1, 3}.
inline std::vector<int> indices_of(unsigned blade) {
  std::vector<int> idx;
  for (int i = 0; i < 32; ++i)
    if (blade & (1u << i)) idx.push_back(i);
  return idx;
}

inline unsigned blade_of(const std::vector<int>& idx) {
  unsigned b = 0;
  for (int i : idx) {
    assert((b & (1u << i)) == 0);
    b |= 1u << i;
  }
  return b;
}

inline int grade_of(unsigned blade) { return int(indices_of(blade).size()); }

// Bubble-sorts `list` ascending and returns the number of adjacent swaps it took.
inline int bubble_sort_count_swaps(std::vector<int>& list) {
  int swaps = 0;
  for (std::size_t pass = 0; pass < list.size(); ++pass)
    for (std::size_t k = 0; k + 1 < list.size(); ++k)
      if (list[k] > list[k + 1]) {
        std::swap(list[k], list[k + 1]);
        ++swaps;
      }
  return swaps;
}

struct SignedBlade {
  double sign;
  unsigned blade;
};

// e_A e_B for basis blades A, B: sort the concatenated factor list counting swaps, then cancel
// equal neighbours (e_i e_i = 1). Equal indices are adjacent once the list is sorted.
inline SignedBlade blade_product(unsigned a, unsigned b) {
  std::vector<int> list = indices_of(a);
  const std::vector<int> lb = indices_of(b);
  list.insert(list.end(), lb.begin(), lb.end());
  const int swaps = bubble_sort_count_swaps(list);
  std::vector<int> kept;
  for (std::size_t k = 0; k < list.size();) {
    if (k + 1 < list.size() && list[k] == list[k + 1]) {
      k += 2;  // e_i e_i = +1
    } else {
      kept.push_back(list[k]);
      k += 1;
    }
  }
  return SignedBlade{swaps % 2 == 0 ? 1.0 : -1.0, blade_of(kept)};
}

// Reverse of a basis blade: write its factors backwards and count the swaps to sort them again.
inline double blade_reverse_sign(unsigned a) {
  std::vector<int> list = indices_of(a);
  std::reverse(list.begin(), list.end());
  return bubble_sort_count_swaps(list) % 2 == 0 ? 1.0 : -1.0;
}

// A multivector of G(R^n): c[bitmask] is the coefficient of that basis blade.
struct MV {
  int n = 0;
  std::vector<double> c;

  MV() = default;
  explicit MV(int dim) : n(dim), c(std::size_t(1) << dim, 0.0) {}

  static MV scalar(int dim, double s) {
    MV m(dim);
    m.c[0] = s;
    return m;
  }
  static MV basis(int dim, unsigned blade, double coeff = 1.0) {
    MV m(dim);
    m.c[blade] = coeff;
    return m;
  }
  // The vector sum_i v[i] e_i.
  static MV vector(const std::vector<double>& v) {
    MV m(int(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) m.c[1u << i] = v[i];
    return m;
  }
  std::size_t size() const { return c.size(); }
  double operator[](unsigned blade) const { return c[blade]; }
  double& operator[](unsigned blade) { return c[blade]; }

  MV operator+(const MV& o) const {
    assert(n == o.n);
    MV r(n);
    for (std::size_t i = 0; i < c.size(); ++i) r.c[i] = c[i] + o.c[i];
    return r;
  }
  MV operator-(const MV& o) const {
    assert(n == o.n);
    MV r(n);
    for (std::size_t i = 0; i < c.size(); ++i) r.c[i] = c[i] - o.c[i];
    return r;
  }
  MV operator*(double s) const {
    MV r(n);
    for (std::size_t i = 0; i < c.size(); ++i) r.c[i] = c[i] * s;
    return r;
  }
  // Largest absolute coefficient.
  double max_abs() const {
    double m = 0.0;
    for (double x : c) m = std::max(m, std::abs(x));
    return m;
  }
  // Sum of absolute coefficients.
  double norm1() const {
    double m = 0.0;
    for (double x : c) m += std::abs(x);
    return m;
  }
};

// Which grade-projection of the blade product a bilinear product keeps.
enum class Keep { Geometric, Outer, LeftContraction };

// blade_product(x, y) for all x, y < 2^n, memoised per n only to keep the tests fast: every entry is
// still computed by the naive function above.
inline const std::vector<SignedBlade>& blade_product_table(int n) {
  static std::vector<std::vector<SignedBlade>> tables(16);
  assert(n >= 0 && n < 16);
  std::vector<SignedBlade>& t = tables[std::size_t(n)];
  if (t.empty()) {
    const unsigned dim = 1u << n;
    t.resize(std::size_t(dim) * dim);
    for (unsigned x = 0; x < dim; ++x)
      for (unsigned y = 0; y < dim; ++y) t[std::size_t(x) * dim + y] = blade_product(x, y);
  }
  return t;
}

inline MV product(const MV& a, const MV& b, Keep keep) {
  assert(a.n == b.n);
  const std::vector<SignedBlade>& table = blade_product_table(a.n);
  std::vector<int> grades(a.size());
  for (unsigned x = 0; x < a.size(); ++x) grades[x] = grade_of(x);
  MV out(a.n);
  for (unsigned x = 0; x < a.size(); ++x) {
    if (a[x] == 0.0) continue;
    for (unsigned y = 0; y < b.size(); ++y) {
      if (b[y] == 0.0) continue;
      const SignedBlade p = table[std::size_t(x) * a.size() + y];
      const int r = grades[x], s = grades[y], g = grades[p.blade];
      bool keep_it = true;
      if (keep == Keep::Outer) keep_it = (g == r + s);
      if (keep == Keep::LeftContraction) keep_it = (s >= r && g == s - r);
      if (keep_it) out[p.blade] += p.sign * a[x] * b[y];
    }
  }
  return out;
}

inline MV gp(const MV& a, const MV& b) { return product(a, b, Keep::Geometric); }
inline MV outer(const MV& a, const MV& b) { return product(a, b, Keep::Outer); }
inline MV left_contraction(const MV& a, const MV& b) { return product(a, b, Keep::LeftContraction); }
inline MV operator*(const MV& a, const MV& b) { return gp(a, b); }

inline MV reverse(const MV& a) {
  MV out(a.n);
  for (unsigned x = 0; x < a.size(); ++x) out[x] = blade_reverse_sign(x) * a[x];
  return out;
}

inline MV grade(const MV& a, int g) {
  MV out(a.n);
  for (unsigned x = 0; x < a.size(); ++x)
    if (grade_of(x) == g) out[x] = a[x];
  return out;
}

// R x ~R.
inline MV sandwich(const MV& r, const MV& x) { return gp(gp(r, x), reverse(r)); }

// exp(B) for any multivector B (used for bivectors): Taylor series after scaling B by 2^-s so that its
// coefficients are small, then s squarings. 30 terms of a series of a multivector of norm1 <= 1/2
// leave a remainder below 0.5^30/30! ~ 1e-41.
inline MV exp(const MV& b) {
  int s = 0;
  double n1 = b.norm1();
  while (n1 > 0.5) {
    n1 *= 0.5;
    ++s;
  }
  const MV small = b * std::ldexp(1.0, -s);
  MV sum = MV::scalar(b.n, 1.0);
  MV term = MV::scalar(b.n, 1.0);
  for (int k = 1; k <= 30; ++k) {
    term = gp(term, small) * (1.0 / k);
    sum = sum + term;
  }
  for (int i = 0; i < s; ++i) sum = gp(sum, sum);
  return sum;
}

// ---------------------------------------------------------------- storage orders
// All k-subsets of {0..n-1} as ascending index tuples, in lexicographic order (std::vector's
// operator< is lexicographic). Built by brute force over all 2^n subsets, then sorted.
inline std::vector<std::vector<int>> combinations(int n, int k) {
  std::vector<std::vector<int>> out;
  for (unsigned m = 0; m < (1u << n); ++m) {
    std::vector<int> t = indices_of(m);
    if (int(t.size()) == k) out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The grades a storage layout holds, ascending; within a grade blades are lexicographic.
enum class Layout { Full, Even, Odd, Vector, Bivector };

inline bool holds(Layout l, int g) {
  switch (l) {
    case Layout::Full:
      return true;
    case Layout::Even:
      return g % 2 == 0;
    case Layout::Odd:
      return g % 2 == 1;
    case Layout::Vector:
      return g == 1;
    case Layout::Bivector:
      return g == 2;
  }
  return false;
}

// Position -> blade bitmask of a layout.
inline std::vector<unsigned> order(int n, Layout l) {
  std::vector<unsigned> out;
  for (int g = 0; g <= n; ++g) {
    if (!holds(l, g)) continue;
    for (const std::vector<int>& t : combinations(n, g)) out.push_back(blade_of(t));
  }
  return out;
}

// Storage-ordered coefficients -> multivector.
inline MV from_coeffs(int n, Layout l, const std::vector<double>& coeffs) {
  const std::vector<unsigned> ord = order(n, l);
  assert(coeffs.size() == ord.size());
  MV m(n);
  for (std::size_t i = 0; i < ord.size(); ++i) m[ord[i]] = coeffs[i];
  return m;
}

// Multivector -> storage-ordered coefficients (blades outside the layout are dropped).
inline std::vector<double> to_coeffs(const MV& m, Layout l) {
  const std::vector<unsigned> ord = order(m.n, l);
  std::vector<double> out(ord.size());
  for (std::size_t i = 0; i < ord.size(); ++i) out[i] = m[ord[i]];
  return out;
}

// Largest |coefficient| of the blades that a layout does not hold (e.g. the non-vector part).
inline double max_abs_outside(const MV& m, Layout l) {
  double r = 0.0;
  for (unsigned x = 0; x < m.size(); ++x)
    if (!holds(l, grade_of(x))) r = std::max(r, std::abs(m[x]));
  return r;
}

}  // namespace refga
