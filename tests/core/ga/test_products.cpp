// The fast products of wedge/ga/products.hpp against the slow reference algebra of
// tests/support/reference_ga.hpp (written independently of core/), for every n = 2..6 on random inputs,
// plus identities of unit rotors and the paper's sign conventions (x' = R x ~R, dR/dt = -1/2 w R,
// point velocity x . w).
//
// Tolerances. Inputs are uniform in [-1, 1] (std::mt19937_64, fixed seeds). Fast and reference compute
// the same sums of products, only in a different order, so they differ by round-off alone. For a
// bilinear product P(a, b) every output coefficient is a signed sum of at most 2^n <= 64 products
// a_i b_j, whose absolute values add up to at most S = |a|_1 |b|_1 (sums of absolute coefficients);
// the textbook summation bound gives |fl(sum) - sum| <= gamma_64 S ~ 7.1e-15 S for each of the two
// implementations. We allow kRel * S with kRel = 1e-12 (a margin of ~70 over the worst case, so only a
// wrong sign, a missing or a misplaced term can fail: those are O(1) errors). Sandwiches R x ~R are
// two products, scale S = |R|_1^2 |x|_1. Pure data movement (reverse, grade projection, layouts) must
// be bit-exact. Identities of unit rotors (coefficients <= 1, |R|_1 <= sqrt(32)) use an absolute
// 1e-12, except "R x ~R has no non-vector part", which is checked to 1e-14 as that part cancels
// exactly in exact arithmetic and the observed round-off is a few 1e-16 (|x|_inf <= 1).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dense.hpp"
#include "reference_ga.hpp"
#include "wedge/ga/products.hpp"

namespace {

using refga::Layout;
using refga::MV;
using wedge::Bivector;
using wedge::Mat;
using wedge::Multivector;
using wedge::Rotor;
using wedge::Vec;

constexpr int kSamples = 200;
constexpr double kRel = 1e-12;      // relative to the a-priori magnitude S of the result, see above
constexpr double kUnitTol = 1e-12;  // identities of unit rotors, O(1) quantities
constexpr double kPureTol = 1e-14;  // the non-vector part of a rotated vector

template <class E>
std::vector<double> stdvec(const Eigen::DenseBase<E>& v) {
  std::vector<double> out(std::size_t(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) out[std::size_t(i)] = v.derived()(i);
  return out;
}

// Fast typed values -> reference multivectors, through the reference's own storage orders.
template <int N>
MV ref(const Vec<N>& v) {
  return refga::from_coeffs(N, Layout::Vector, stdvec(v));
}
template <int N>
MV ref(const Bivector<N>& b) {
  return refga::from_coeffs(N, Layout::Bivector, stdvec(b.coeffs()));
}
template <int N>
MV ref(const Rotor<N>& r) {
  return refga::from_coeffs(N, Layout::Even, stdvec(r.coeffs()));
}
template <int N>
MV ref(const Multivector<N>& m) {
  return refga::from_coeffs(N, Layout::Full, stdvec(m.coeffs()));
}

// Reference multivectors -> fast typed values (blades outside the layout are dropped).
template <int N>
Rotor<N> fast_rotor(const MV& m) {
  const std::vector<double> c = refga::to_coeffs(m, Layout::Even);
  Rotor<N> r;
  for (int i = 0; i < wedge::kEven<N>; ++i) r[i] = c[std::size_t(i)];
  return r;
}
template <int N>
Vec<N> fast_vec(const MV& m) {
  const std::vector<double> c = refga::to_coeffs(m, Layout::Vector);
  Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = c[std::size_t(i)];
  return v;
}
template <int N>
Bivector<N> fast_biv(const MV& m) {
  const std::vector<double> c = refga::to_coeffs(m, Layout::Bivector);
  Bivector<N> b;
  for (int i = 0; i < wedge::kBiv<N>; ++i) b[i] = c[std::size_t(i)];
  return b;
}

std::string show(const std::vector<double>& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(";
  for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
  s << ")";
  return s.str();
}
template <class E>
std::string show(const Eigen::DenseBase<E>& v) {
  std::ostringstream s;
  s << v.derived().format(Eigen::IOFormat(17, Eigen::DontAlignCols, ", ", "; ", "", "", "[", "]"));  // rows split by ;
  return s.str();
}

// Collects comparisons of one quantity; reports the first few failures in full (with the inputs),
// then one CHECK per quantity so that the output stays short.
class Compare {
 public:
  Compare(std::string what, int n) : what_(std::move(what)), n_(n) {}
  ~Compare() {
    if (std::getenv("WEDGE_GA_VERBOSE"))
      std::cout << "n=" << n_ << " " << what_ << ": " << count_ << " comparisons, worst |diff|/tol = " << worst_
                << "\n";
    INFO(what_ << " (n = " << n_ << "): " << failures_ << " of " << count_ << " comparisons failed");
    CHECK(failures_ == 0);
  }
  template <class Describe>
  void operator()(const std::vector<double>& fast, const std::vector<double>& expected, double tol,
                  Describe&& describe) {
    ++count_;
    double err = fast.size() == expected.size() ? 0.0 : INFINITY;
    for (std::size_t i = 0; i < fast.size() && i < expected.size(); ++i) {
      const double d = std::abs(fast[i] - expected[i]);
      err = std::isfinite(d) ? std::max(err, d) : INFINITY;
    }
    if (tol > 0) worst_ = std::max(worst_, err / tol);
    if (err <= tol) return;
    if (++failures_ <= 3)
      FAIL_CHECK(what_ << " (n = " << n_ << "): max |fast - reference| = " << err << " > tol " << tol
                       << "\n  fast      = " << show(fast) << "\n  reference = " << show(expected) << "\n  "
                       << describe());
  }
  void operator()(double fast, double expected, double tol) {
    (*this)(std::vector<double>{fast}, std::vector<double>{expected}, tol, [] { return std::string(); });
  }

 private:
  std::string what_;
  int n_;
  int count_ = 0, failures_ = 0;
  double worst_ = 0.0;
};

template <int N>
struct Random {
  std::mt19937_64 rng;
  explicit Random(std::uint64_t seed) : rng(seed + std::uint64_t(N)) {}
  double u() { return std::uniform_real_distribution<double>(-1.0, 1.0)(rng); }
  template <class T>
  T fill() {
    T t;
    for (int i = 0; i < T::size(); ++i) t[i] = u();
    return t;
  }
  Vec<N> vec() {
    Vec<N> v;
    for (int i = 0; i < N; ++i) v[i] = u();
    return v;
  }
  Mat<N> mat() {
    Mat<N> m;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) m(i, j) = u();
    return m;
  }
  Bivector<N> biv() { return fill<Bivector<N>>(); }
  Rotor<N> even() { return fill<Rotor<N>>(); }  // a general even multivector, not a unit rotor
  Multivector<N> mv() { return fill<Multivector<N>>(); }
  std::vector<double> unit_vector() {
    for (;;) {
      std::vector<double> v(N);
      double n2 = 0;
      for (double& x : v) {
        x = u();
        n2 += x * x;
      }
      if (n2 < 0.01) continue;
      for (double& x : v) x /= std::sqrt(n2);
      return v;
    }
  }
  // A unit rotor as the reference geometric product of an even number (2 .. 2 ceil(N/2)) of unit vectors.
  MV unit_rotor_ref() {
    const int pairs = 1 + int(rng() % std::uint64_t((N + 1) / 2));
    MV r = MV::scalar(N, 1.0);
    for (int k = 0; k < 2 * pairs; ++k) r = refga::gp(r, MV::vector(unit_vector()));
    return r;
  }
};

// The N x N identity and basis vectors, as reference multivectors.
MV ref_basis_vector(int n, int i) { return MV::basis(n, 1u << i); }

// The second compound of M in the reference's bivector order: entry ((a,b),(i,j)) = det M[{a,b},{i,j}].
template <int N>
wedge::BivMat<N> compound(const Mat<N>& m) {
  const auto pairs = refga::combinations(N, 2);
  wedge::BivMat<N> c;
  for (std::size_t col = 0; col < pairs.size(); ++col)
    for (std::size_t row = 0; row < pairs.size(); ++row) {
      const int a = pairs[row][0], b = pairs[row][1], i = pairs[col][0], j = pairs[col][1];
      c(Eigen::Index(row), Eigen::Index(col)) = m(a, i) * m(b, j) - m(a, j) * m(b, i);
    }
  return c;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
TEST_CASE("reference GA: basis products, storage orders and exp are the textbook ones", "[ga]") {
  for (int n = 2; n <= 6; ++n) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const refga::SignedBlade p = refga::blade_product(1u << i, 1u << j);
        if (i == j) {
          CHECK(p.sign == 1.0);  // e_i e_i = 1
          CHECK(p.blade == 0u);
        } else {
          CHECK(p.blade == ((1u << i) | (1u << j)));
          CHECK(p.sign == (i < j ? 1.0 : -1.0));  // e_i e_j = e_ij = -e_j e_i
        }
      }
  }
  // e01 e01 = -1, e1 e02 = e1 e0 e2 = -e012, e012 e2 = e01, e01 e12 = e02, reverse signs + - - + + - - +.
  CHECK(refga::blade_product(0b11, 0b11).sign == -1.0);
  CHECK(refga::blade_product(0b11, 0b11).blade == 0u);
  CHECK(refga::blade_product(0b010, 0b101).sign == -1.0);
  CHECK(refga::blade_product(0b010, 0b101).blade == 0b111u);
  CHECK(refga::blade_product(0b111, 0b100).sign == 1.0);
  CHECK(refga::blade_product(0b111, 0b100).blade == 0b011u);
  CHECK(refga::blade_product(0b011, 0b110).sign == 1.0);
  CHECK(refga::blade_product(0b011, 0b110).blade == 0b101u);
  const double rev[] = {1, 1, -1, -1, 1, 1, -1, -1};
  for (int g = 0; g < 7; ++g) CHECK(refga::blade_reverse_sign((1u << g) - 1u) == rev[g]);

  // The orders, literally, for n = 4.
  using V = std::vector<unsigned>;
  CHECK(refga::order(4, Layout::Full) == V{0, 0b1, 0b10, 0b100, 0b1000, 0b11, 0b101, 0b1001, 0b110, 0b1010, 0b1100,
                                           0b111, 0b1011, 0b1101, 0b1110, 0b1111});
  CHECK(refga::order(4, Layout::Bivector) == V{0b11, 0b101, 0b1001, 0b110, 0b1010, 0b1100});
  CHECK(refga::order(4, Layout::Even) == V{0, 0b11, 0b101, 0b1001, 0b110, 0b1010, 0b1100, 0b1111});
  CHECK(refga::order(4, Layout::Odd) == V{0b1, 0b10, 0b100, 0b1000, 0b111, 0b1011, 0b1101, 0b1110});
  CHECK(refga::order(3, Layout::Vector) == V{0b1, 0b10, 0b100});
  for (int n = 2; n <= 6; ++n) {
    CHECK(refga::order(n, Layout::Full).size() == (1u << n));
    CHECK(refga::order(n, Layout::Even).size() == (1u << (n - 1)));
    CHECK(refga::order(n, Layout::Bivector).size() == unsigned(n * (n - 1) / 2));
  }

  // Associativity, and a b = a . b + a ^ b for vectors, on random inputs.
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 2; n <= 6; ++n) {
    for (int s = 0; s < 10; ++s) {
      MV a(n), b(n), c(n);
      for (std::size_t k = 0; k < a.size(); ++k) {
        a.c[k] = u(rng);
        b.c[k] = u(rng);
        c.c[k] = u(rng);
      }
      const double scale = a.norm1() * b.norm1() * c.norm1();
      CHECK(((a * b) * c - a * (b * c)).max_abs() <= kRel * scale);
      std::vector<double> x(static_cast<std::size_t>(n)), y(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        x[std::size_t(i)] = u(rng);
        y[std::size_t(i)] = u(rng);
      }
      const MV xv = MV::vector(x), yv = MV::vector(y);
      double dotxy = 0;
      for (int i = 0; i < n; ++i) dotxy += x[std::size_t(i)] * y[std::size_t(i)];
      CHECK((xv * yv - refga::left_contraction(xv, yv) - refga::outer(xv, yv)).max_abs() <= 1e-15);
      CHECK(std::abs(refga::left_contraction(xv, yv)[0] - dotxy) <= 1e-15);
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          CHECK(std::abs(refga::outer(xv, yv)[(1u << i) | (1u << j)] -
                         (x[std::size_t(i)] * y[std::size_t(j)] - x[std::size_t(j)] * y[std::size_t(i)])) <= 1e-15);
    }
  }

  // exp(t e01) = cos t + sin t e01, and exp(B) exp(-B) = 1.
  for (double t : {0.0, 0.3, 2.0, 7.0, -11.0}) {
    const MV r = refga::exp(MV::basis(4, 0b11, t));
    MV expect = MV::scalar(4, std::cos(t));
    expect[0b11] = std::sin(t);
    CHECK((r - expect).max_abs() <= 1e-13);
  }
  for (int s = 0; s < 10; ++s) {
    MV b(5);
    for (unsigned blade : refga::order(5, Layout::Bivector)) b[blade] = 2.0 * u(rng);
    CHECK((refga::exp(b) * refga::exp(b * -1.0) - MV::scalar(5, 1.0)).max_abs() <= 1e-12);
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: fast storage layouts match the reference orders", "[ga]", ((int N), N), 2, 3, 4, 5, 6) {
  Random<N> rnd(1);
  const auto biv_order = refga::order(N, Layout::Bivector);
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) {
      const unsigned blade = (1u << i) | (1u << j);
      int pos = -1;
      for (std::size_t p = 0; p < biv_order.size(); ++p)
        if (biv_order[p] == blade) pos = int(p);
      CHECK(Bivector<N>::index(i, j) == pos);
      CHECK(ref(Bivector<N>::basis(i, j)).c == MV::basis(N, blade).c);
    }
  for (int s = 0; s < 20; ++s) {
    const Multivector<N> m = rnd.mv();
    const MV rm = ref(m);
    for (unsigned blade = 0; blade < (1u << N); ++blade) CHECK(m.blade(blade) == rm[blade]);
    const Vec<N> v = rnd.vec();
    const Bivector<N> b = rnd.biv();
    const Rotor<N> r = rnd.even();
    CHECK(ref(wedge::to_multivector(v)).c == ref(v).c);
    CHECK(ref(wedge::to_multivector(b)).c == ref(b).c);
    CHECK(ref(wedge::to_multivector(r)).c == ref(r).c);
    CHECK(ref(wedge::vector_part(m)).c == refga::grade(rm, 1).c);
    CHECK(ref(wedge::bivector_part(m)).c == refga::grade(rm, 2).c);
    MV even(N);
    for (int g = 0; g <= N; g += 2) even = even + refga::grade(rm, g);
    CHECK(ref(wedge::even_part(m)).c == even.c);
    CHECK(r.bivector().coeffs() == fast_biv<N>(ref(r)).coeffs());
    CHECK(r.scalar() == ref(r)[0]);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        if (i != j) CHECK(b(i, j) == ref(b)[(1u << i) | (1u << j)] * (i < j ? 1.0 : -1.0));
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: general multivector products match the reference", "[ga]", ((int N), N), 2, 3, 4, 5, 6) {
  Random<N> rnd(2);
  Compare geometric("geometric product a*b", N), outer("outer(a, b)", N), lc("left_contraction(a, b)", N),
      rev("reverse(a)", N), grd("grade(a, g)", N);
  for (int s = 0; s < kSamples; ++s) {
    const Multivector<N> a = rnd.mv(), b = rnd.mv();
    const MV ra = ref(a), rb = ref(b);
    const double tol = kRel * ra.norm1() * rb.norm1();
    const auto inputs = [&] { return "a = " + show(a.coeffs()) + "\n  b = " + show(b.coeffs()); };
    geometric(stdvec((a * b).coeffs()), refga::to_coeffs(refga::gp(ra, rb), Layout::Full), tol, inputs);
    outer(stdvec(wedge::outer(a, b).coeffs()), refga::to_coeffs(refga::outer(ra, rb), Layout::Full), tol, inputs);
    lc(stdvec(wedge::left_contraction(a, b).coeffs()), refga::to_coeffs(refga::left_contraction(ra, rb), Layout::Full),
       tol, inputs);
    rev(stdvec(wedge::reverse(a).coeffs()), refga::to_coeffs(refga::reverse(ra), Layout::Full), 0.0, inputs);
    for (int g = 0; g <= N; ++g)
      grd(stdvec(wedge::grade(a, g).coeffs()), refga::to_coeffs(refga::grade(ra, g), Layout::Full), 0.0, inputs);
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: vector and bivector products match the reference", "[ga]", ((int N), N), 2, 3, 4, 5, 6) {
  Random<N> rnd(3);
  Compare wedge_vv("outer(Vec, Vec)", N), dot_vb("dot(Vec r, Bivector w) = r _| w", N),
      comm("commutator(A, B) = (AB - BA)/2", N), comm_pure("(AB - BA)/2 is a pure bivector (reference)", N),
      sp("scalar_product(A, B) = <AB>_0", N), gen("generator_matrix(w) x = x . w", N),
      gen_inv("bivector_from_generator(generator_matrix(w)) = w", N), wm("wedge_matrix(r) a = r ^ a", N),
      wmt("wedge_matrix(r)^T w = r . w", N);
  for (int s = 0; s < kSamples; ++s) {
    const Vec<N> r = rnd.vec(), a = rnd.vec();
    const Bivector<N> w = rnd.biv(), v = rnd.biv();
    const MV rr = ref(r), ra = ref(a), rw = ref(w), rv = ref(v);
    const auto inputs = [&] {
      return "r = " + show(r) + "\n  a = " + show(a) + "\n  w = " + show(w.coeffs()) + "\n  v = " + show(v.coeffs());
    };
    const double s_ra = kRel * rr.norm1() * ra.norm1(), s_rw = kRel * rr.norm1() * rw.norm1(),
                 s_wv = kRel * rw.norm1() * rv.norm1();

    const MV r_wedge_a = refga::outer(rr, ra), r_dot_w = refga::left_contraction(rr, rw);
    wedge_vv(stdvec(wedge::outer(r, a).coeffs()), refga::to_coeffs(r_wedge_a, Layout::Bivector), s_ra, inputs);
    dot_vb(stdvec(wedge::dot(r, w)), refga::to_coeffs(r_dot_w, Layout::Vector), s_rw, inputs);

    const MV c = (rw * rv - rv * rw) * 0.5;
    comm(stdvec(wedge::commutator(w, v).coeffs()), refga::to_coeffs(c, Layout::Bivector), s_wv, inputs);
    comm_pure({refga::max_abs_outside(c, Layout::Bivector)}, {0.0}, s_wv, inputs);
    sp(wedge::scalar_product(w, v), (rw * rv)[0], s_wv);

    const Mat<N> g = wedge::generator_matrix(w);
    gen(stdvec(Vec<N>(g * r)), refga::to_coeffs(r_dot_w, Layout::Vector), s_rw, inputs);
    for (int j = 0; j < N; ++j)
      gen(stdvec(Vec<N>(g.col(j))),
          refga::to_coeffs(refga::left_contraction(ref_basis_vector(N, j), rw), Layout::Vector), kRel * rw.norm1(),
          inputs);
    gen_inv(stdvec(wedge::bivector_from_generator(g).coeffs()), stdvec(w.coeffs()), 0.0, inputs);

    const wedge::WedgeMat<N> m = wedge::wedge_matrix(r);
    wm(stdvec(Eigen::Matrix<double, wedge::kBiv<N>, 1>(m * a)), refga::to_coeffs(r_wedge_a, Layout::Bivector), s_ra,
       inputs);
    wmt(stdvec(Vec<N>(m.transpose() * w.coeffs())), refga::to_coeffs(r_dot_w, Layout::Vector), s_rw, inputs);
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: rotor products, sandwiches and matrix forms match the reference", "[ga]", ((int N), N), 2,
                       3, 4, 5, 6) {
  Random<N> rnd(4);
  Compare prod("Rotor * Rotor", N), rev("reverse(Rotor)", N), rot_v("rotate(R, Vec) = <R x ~R>_1", N),
      rot_b("rotate(R, Bivector) = <R B ~R>_2", N), rot_iv("rotate_inverse(R, Vec) = <~R x R>_1", N),
      rot_ib("rotate_inverse(R, Bivector) = <~R B R>_2", N), mat("to_matrix(R) column i = <R e_i ~R>_1", N),
      bm("bivector_matrix(unit R) column c = R e_c ~R", N),
      bm_m("bivector_matrix(M) column (ij) = (M e_i) ^ (M e_j)", N);
  const auto biv_order = refga::order(N, Layout::Bivector);
  for (int s = 0; s < kSamples; ++s) {
    // General even multivectors: every product below is a (bi)linear formula valid for any of them.
    const Rotor<N> p = rnd.even(), q = rnd.even();
    const Vec<N> x = rnd.vec();
    const Bivector<N> b = rnd.biv();
    const MV rp = ref(p), rq = ref(q), rx = ref(x), rb = ref(b);
    const auto inputs = [&] {
      return "R = " + show(p.coeffs()) + "\n  Q = " + show(q.coeffs()) + "\n  x = " + show(x) +
             "\n  B = " + show(b.coeffs());
    };
    const double pp = rp.norm1() * rp.norm1();
    prod(stdvec((p * q).coeffs()), refga::to_coeffs(rp * rq, Layout::Even), kRel * rp.norm1() * rq.norm1(), inputs);
    rev(stdvec(wedge::reverse(p).coeffs()), refga::to_coeffs(refga::reverse(rp), Layout::Even), 0.0, inputs);
    rot_v(stdvec(wedge::rotate(p, x)), refga::to_coeffs(refga::sandwich(rp, rx), Layout::Vector),
          kRel * pp * rx.norm1(), inputs);
    rot_b(stdvec(wedge::rotate(p, b).coeffs()), refga::to_coeffs(refga::sandwich(rp, rb), Layout::Bivector),
          kRel * pp * rb.norm1(), inputs);
    rot_iv(stdvec(wedge::rotate_inverse(p, x)),
           refga::to_coeffs(refga::sandwich(refga::reverse(rp), rx), Layout::Vector), kRel * pp * rx.norm1(), inputs);
    rot_ib(stdvec(wedge::rotate_inverse(p, b).coeffs()),
           refga::to_coeffs(refga::sandwich(refga::reverse(rp), rb), Layout::Bivector), kRel * pp * rb.norm1(), inputs);
    const Mat<N> m = wedge::to_matrix(p);
    for (int i = 0; i < N; ++i)
      mat(stdvec(Vec<N>(m.col(i))), refga::to_coeffs(refga::sandwich(rp, ref_basis_vector(N, i)), Layout::Vector),
          kRel * pp, inputs);

    // [R]_2 is R B ~R only for unit rotors (for R = s U it scales like s^4, the sandwich like s^2).
    const MV ru = rnd.unit_rotor_ref();
    const Rotor<N> unit = fast_rotor<N>(ru);
    const wedge::BivMat<N> b2 = wedge::bivector_matrix(unit);
    for (std::size_t c = 0; c < biv_order.size(); ++c)
      bm(stdvec(Eigen::Matrix<double, wedge::kBiv<N>, 1>(b2.col(Eigen::Index(c)))),
         refga::to_coeffs(refga::sandwich(ru, MV::basis(N, biv_order[c])), Layout::Bivector),
         kRel * ru.norm1() * ru.norm1(), [&] { return "unit R = " + show(unit.coeffs()); });

    // The compound of an arbitrary matrix.
    const Mat<N> a = rnd.mat();
    const wedge::BivMat<N> am = wedge::bivector_matrix(a);
    for (std::size_t c = 0; c < biv_order.size(); ++c) {
      const int i = refga::indices_of(biv_order[c])[0], j = refga::indices_of(biv_order[c])[1];
      const MV ci = ref(Vec<N>(a.col(i))), cj = ref(Vec<N>(a.col(j)));
      bm_m(stdvec(Eigen::Matrix<double, wedge::kBiv<N>, 1>(am.col(Eigen::Index(c)))),
           refga::to_coeffs(refga::outer(ci, cj), Layout::Bivector), kRel * ci.norm1() * cj.norm1(),
           [&] { return "M = " + show(a); });
    }
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: identities of unit rotors hold", "[ga]", ((int N), N), 2, 3, 4, 5, 6) {
  Random<N> rnd(5);
  Compare unit("R ~R = ~R R = 1", N), len("|R x ~R| = |x|", N), pure_fast("<R x ~R>_(!=1) = 0 (fast multivectors)", N),
      pure_ref("<R x ~R>_(!=1) = 0 (reference)", N), orth("to_matrix(R)^T to_matrix(R) = I", N),
      det("det to_matrix(R) = +1", N), act("to_matrix(R) x = rotate(R, x)", N),
      compose("to_matrix(A*B) = to_matrix(A) to_matrix(B)", N), inv("rotate_inverse(R, rotate(R, x)) = x", N),
      b2orth("[R]_2^T [R]_2 = I", N), b2comp("[R]_2 = second compound of to_matrix(R)", N),
      b2act("[R]_2 B = rotate(R, B)", N), b2compose("[AB]_2 = [A]_2 [B]_2", N);
  for (int s = 0; s < kSamples; ++s) {
    const MV ra = rnd.unit_rotor_ref(), rb = rnd.unit_rotor_ref();
    const Rotor<N> r = fast_rotor<N>(ra), q = fast_rotor<N>(rb);
    const Vec<N> x = rnd.vec();
    const Bivector<N> w = rnd.biv();
    const auto inputs = [&] {
      return "R = " + show(r.coeffs()) + "\n  Q = " + show(q.coeffs()) + "\n  x = " + show(x) +
             "\n  w = " + show(w.coeffs());
    };
    const auto id = stdvec(Rotor<N>::identity().coeffs());
    unit(stdvec((r * wedge::reverse(r)).coeffs()), id, kUnitTol, inputs);
    unit(stdvec((wedge::reverse(r) * r).coeffs()), id, kUnitTol, inputs);

    const Vec<N> y = wedge::rotate(r, x);
    len(y.norm(), x.norm(), kUnitTol * x.norm());
    const Multivector<N> mr = wedge::to_multivector(r);
    const Multivector<N> full = mr * wedge::to_multivector(x) * wedge::reverse(mr);
    pure_fast({refga::max_abs_outside(ref(full), Layout::Vector)}, {0.0}, kPureTol, inputs);
    pure_ref({refga::max_abs_outside(refga::sandwich(ra, ref(x)), Layout::Vector)}, {0.0}, kPureTol, inputs);

    const Mat<N> m = wedge::to_matrix(r), mq = wedge::to_matrix(q);
    orth(stdvec(Mat<N>(m.transpose() * m).reshaped()), stdvec(Mat<N>(Mat<N>::Identity()).reshaped()), kUnitTol, inputs);
    det(::det(m), 1.0, kUnitTol);
    act(stdvec(Vec<N>(m * x)), stdvec(y), kUnitTol, inputs);
    compose(stdvec(Mat<N>(wedge::to_matrix(r * q)).reshaped()), stdvec(Mat<N>(m * mq).reshaped()), kUnitTol, inputs);
    inv(stdvec(wedge::rotate_inverse(r, y)), stdvec(x), kUnitTol, inputs);

    using BM = wedge::BivMat<N>;
    const BM b2 = wedge::bivector_matrix(r), b2q = wedge::bivector_matrix(q);
    b2orth(stdvec(BM(b2.transpose() * b2).reshaped()), stdvec(BM(BM::Identity()).reshaped()), kUnitTol, inputs);
    b2comp(stdvec(BM(b2).reshaped()), stdvec(BM(compound<N>(m)).reshaped()), kUnitTol, inputs);
    b2act(stdvec(Eigen::Matrix<double, wedge::kBiv<N>, 1>(b2 * w.coeffs())), stdvec(wedge::rotate(r, w).coeffs()),
          kUnitTol, inputs);
    b2compose(stdvec(BM(wedge::bivector_matrix(r * q)).reshaped()), stdvec(BM(b2 * b2q).reshaped()), kUnitTol, inputs);
  }
}

// ------------------------------------------------------------------------------------------------
TEMPLATE_TEST_CASE_SIG("ga: dR/dt = -1/2 w R moves a point with velocity x . w", "[ga]", ((int N), N), 2, 3, 4, 5, 6) {
  // A worked example: R(t) = exp(-t e01 / 2) turns e0 towards e1, and e0 . e01 = e1.
  const MV e01 = MV::basis(N, 0b11);
  for (double t : {0.1, 1.0, 2.5}) {
    const Rotor<N> rt = fast_rotor<N>(refga::exp(e01 * (-0.5 * t)));
    Vec<N> expect = Vec<N>::Zero();
    expect[0] = std::cos(t);
    expect[1] = std::sin(t);
    CHECK((wedge::rotate(rt, Vec<N>(Vec<N>::Unit(0))) - expect).norm() <= 1e-14);
  }
  CHECK(wedge::dot(Vec<N>(Vec<N>::Unit(0)), Bivector<N>::basis(0, 1)) == Vec<N>(Vec<N>::Unit(1)));

  // Random: R(t) = exp(-t w / 2) R0 solves dR/dt = -1/2 w R with R(0) = R0. The central difference of
  // x(t) = R(t) x0 ~R(t) with h = 1e-5 has truncation error h^2/6 |x'''| <= 1.7e-11 |w|^3 |x0| (< 3e-9
  // here) and round-off ~ 1e-16 / h = 1e-11; the opposite sign convention would be off by 2 |x . w| = O(1).
  Random<N> rnd(6);
  Compare vel("(x(h) - x(-h)) / 2h = x(0) . w", N);
  const double h = 1e-5;
  for (int s = 0; s < 50; ++s) {
    const MV r0 = rnd.unit_rotor_ref();
    const Bivector<N> w = rnd.biv();
    const Vec<N> x0 = rnd.vec();
    const auto at = [&](double t) { return fast_rotor<N>(refga::gp(refga::exp(ref(w) * (-0.5 * t)), r0)); };
    const Vec<N> x = wedge::rotate(at(0.0), x0);
    const Vec<N> fd = (wedge::rotate(at(h), x0) - wedge::rotate(at(-h), x0)) / (2 * h);
    vel(stdvec(fd), stdvec(wedge::dot(x, w)), 1e-7, [&] {
      return "w = " + show(w.coeffs()) + "\n  x0 = " + show(x0) +
             "\n  R0 = " + show(refga::to_coeffs(r0, Layout::Even));
    });
  }
}

// The expansion written above rotate() in products.hpp, term for term, against the kernel on general
// even elements (the vector part of R x ~R, unit or not). Inputs in [-1, 1]: each component is a sum of
// at most 32 products of three factors, so the two orders of summation agree to well within 1e-13.
TEST_CASE("ga: rotate computes the expansion its comment gives in 3D and 4D", "[ga]") {
  Random<3> r3(21);
  for (int k = 0; k < 200; ++k) {
    const Rotor<3> r = r3.even();
    const Vec<3> x = r3.vec();
    const double s = r[0], b01 = r[1], b02 = r[2], b12 = r[3];
    Vec<3> e;
    e[0] = (s * s - b01 * b01 - b02 * b02 + b12 * b12) * x[0] + 2 * (s * b01 - b02 * b12) * x[1] +
           2 * (s * b02 + b01 * b12) * x[2];
    e[1] = -2 * (s * b01 + b02 * b12) * x[0] + (s * s - b01 * b01 + b02 * b02 - b12 * b12) * x[1] +
           2 * (s * b12 - b01 * b02) * x[2];
    e[2] = 2 * (b01 * b12 - s * b02) * x[0] - 2 * (s * b12 + b01 * b02) * x[1] +
           (s * s + b01 * b01 - b02 * b02 - b12 * b12) * x[2];
    CHECK((rotate(r, x) - e).norm() < 1e-13);
  }
  Random<4> r4(22);
  for (int k = 0; k < 200; ++k) {
    const Rotor<4> r = r4.even();
    const Vec<4> x = r4.vec();
    const double s = r[0], b01 = r[1], b02 = r[2], b03 = r[3], b12 = r[4], b13 = r[5], b23 = r[6], p = r[7];
    const double ss = s * s - p * p;
    Vec<4> e;
    e[0] = (ss - b01 * b01 - b02 * b02 - b03 * b03 + b12 * b12 + b13 * b13 + b23 * b23) * x[0] +
           2 * (s * b01 + p * b23 - b02 * b12 - b03 * b13) * x[1] + 2 * (s * b02 - p * b13 + b01 * b12 - b03 * b23) * x[2] +
           2 * (s * b03 + p * b12 + b01 * b13 + b02 * b23) * x[3];
    e[1] = -2 * (s * b01 + p * b23 + b02 * b12 + b03 * b13) * x[0] +
           (ss - b01 * b01 + b02 * b02 + b03 * b03 - b12 * b12 - b13 * b13 + b23 * b23) * x[1] +
           2 * (s * b12 + p * b03 - b01 * b02 - b13 * b23) * x[2] + 2 * (s * b13 - p * b02 - b01 * b03 + b12 * b23) * x[3];
    e[2] = 2 * (p * b13 - s * b02 + b01 * b12 - b03 * b23) * x[0] - 2 * (s * b12 + p * b03 + b01 * b02 + b13 * b23) * x[1] +
           (ss + b01 * b01 - b02 * b02 + b03 * b03 - b12 * b12 + b13 * b13 - b23 * b23) * x[2] +
           2 * (s * b23 + p * b01 - b02 * b03 - b12 * b13) * x[3];
    e[3] = 2 * (b01 * b13 + b02 * b23 - s * b03 - p * b12) * x[0] + 2 * (p * b02 - s * b13 - b01 * b03 + b12 * b23) * x[1] -
           2 * (s * b23 + p * b01 + b02 * b03 + b12 * b13) * x[2] +
           (ss + b01 * b01 + b02 * b02 - b03 * b03 + b12 * b12 - b13 * b13 - b23 * b23) * x[3];
    CHECK((rotate(r, x) - e).norm() < 1e-13);
  }
}
