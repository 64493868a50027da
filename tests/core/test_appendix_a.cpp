// The paper's appendix A ("Bivector operator and inertia tensor matrices"), transcribed literally, against
// wedge_matrix (the k x n matrix [r]_* with r ^ a = [r]_* a, r . w = [r]_*^T w, paper eq. 3) and against
// Delta I = [r]_* [r]_*^T, entry by entry, for 2D, 3D and 4D. The symbols x, y, z, w of the paper are
// the coordinates r = (x, y, z, w) = (r[0], r[1], r[2], r[3]); rows and columns of the bivector side
// are in the paper's lexicographic order e_xy, e_xz, (e_xw,) e_yz, (e_yw, e_zw).
//
// Tolerances: [r]_* only copies and negates coordinates, so it must match bit for bit. Every entry of
// Delta I, of [r]_* a and of [r]_*^T w is a sum of at most three products of numbers in [-1, 1] (so at
// most 3 in magnitude); both sides round each product and each addition once (<= 5 roundings of at most
// 2.2e-16 * 4 each), a difference of at most ~5e-15, so 1e-14 separates round-off from any wrong entry
// (an O(1) error).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include "appendix_a.hpp"
#include "reference_ga.hpp"
#include "wedge/ga/products.hpp"

namespace {

constexpr int kSamples = 100;
constexpr double kTol = 1e-14;

template <int N>
wedge::Vec<N> random_vec(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  wedge::Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = u(rng);
  return v;
}

template <int N>
refga::MV ref_vec(const wedge::Vec<N>& v) {
  return refga::MV::vector(std::vector<double>(v.data(), v.data() + N));
}

// The paper's matrices against the fast code and the reference algebra, for one r.
template <int N>
void check_against_paper(const wedge::Vec<N>& r, const wedge::WedgeMat<N>& paper_wedge,
                         const wedge::BivMat<N>& paper_delta_i, std::mt19937_64& rng) {
  constexpr int k = wedge::kBiv<N>;
  INFO("r = " << r.transpose());
  const wedge::WedgeMat<N> fast = wedge::wedge_matrix(r);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < N; ++j) {
      INFO("[r]_* entry (" << i << ", " << j << ") (0-based)");
      CHECK(fast(i, j) == paper_wedge(i, j));
    }
  const wedge::BivMat<N> delta_i = fast * fast.transpose();
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      INFO("Delta I entry (" << i << ", " << j << ") (0-based)");
      CHECK(std::abs(delta_i(i, j) - paper_delta_i(i, j)) <= kTol);
    }

  // The paper's [r]_* itself, against the reference algebra: r ^ a = [r]_* a and r . w = [r]_*^T w.
  const auto order = refga::order(N, refga::Layout::Bivector);
  const wedge::Vec<N> a = random_vec<N>(rng);
  const refga::MV r_wedge_a = refga::outer(ref_vec<N>(r), ref_vec<N>(a));
  const Eigen::Matrix<double, k, 1> pa = paper_wedge * a;
  for (int i = 0; i < k; ++i) CHECK(std::abs(pa[i] - r_wedge_a[order[std::size_t(i)]]) <= kTol);

  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix<double, k, 1> w;
  refga::MV rw(N);
  for (int i = 0; i < k; ++i) {
    w[i] = u(rng);
    rw[order[std::size_t(i)]] = w[i];
  }
  const refga::MV r_dot_w = refga::left_contraction(ref_vec<N>(r), rw);
  const wedge::Vec<N> pw = paper_wedge.transpose() * w;
  for (int i = 0; i < N; ++i) CHECK(std::abs(pw[i] - r_dot_w[1u << i]) <= kTol);
}

}  // namespace

template <int N>
void check_dimension(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int s = 0; s < kSamples; ++s) {
    const wedge::Vec<N> r = random_vec<N>(rng);
    check_against_paper<N>(r, paper::wedge_matrix(r), paper::delta_i(r), rng);
  }
}

TEST_CASE("appendix A: 2D [r]_* and Delta I", "[appendix-a]") { check_dimension<2>(2020); }
TEST_CASE("appendix A: 3D [r]_* and Delta I", "[appendix-a]") { check_dimension<3>(2021); }
TEST_CASE("appendix A: 4D [r]_* and Delta I", "[appendix-a]") { check_dimension<4>(2022); }
