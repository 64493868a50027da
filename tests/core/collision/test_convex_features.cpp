// The face lattice used by the separating axis test, against counts known in closed form.
#include <catch2/catch.hpp>

#include "test_util.hpp"
#include "wedge/collision/detail/convex_features.hpp"
#include "wedge/hull.hpp"

using namespace wedge;

namespace {

long long binomial(int n, int k) {
  long long r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// The corners of [-h, h]: the hull route must find what box_features builds combinatorially.
template <int N>
std::vector<Vec<N>> corners(const Vec<N>& h) {
  std::vector<Vec<N>> c;
  for (int m = 0; m < (1 << N); ++m) {
    Vec<N> v;
    for (int i = 0; i < N; ++i) v[i] = (m >> i & 1) ? h[i] : -h[i];
    c.push_back(v);
  }
  return c;
}

}  // namespace

TEMPLATE_TEST_CASE("Box face lattice: 2N facets, C(N,k) direction spaces, 2(N-1) ridge neighbours", "[features]", D2, D3,
                   D4, D5, D6) {
  constexpr int N = TestType::value;
  Vec<N> h;
  for (int i = 0; i < N; ++i) h[i] = 0.3 + 0.2 * i;
  for (const ConvexFeatures<N>& f : {box_features<N>(h), convex_features<N>(convex_hull<N>(corners<N>(h)))}) {
    REQUIRE(f.vertices.size() == std::size_t(1) << N);
    REQUIRE(int(f.facets.size()) == 2 * N);
    for (const auto& facet : f.facets) {
      CHECK(facet.vertices.size() == std::size_t(1) << (N - 1));
      CHECK(int(facet.neighbours.size()) == 2 * (N - 1));
      for (int v : facet.vertices) CHECK(facet.normal.dot(f.vertices[v]) == Approx(facet.offset).margin(1e-12));
    }
    for (int k = 1; k <= N - 2; ++k) CHECK((long long)f.directions[k].size() == binomial(N, k));
  }
}

TEMPLATE_TEST_CASE("Simplex face lattice: N+1 facets with N neighbours, C(N+1,k+1) k-face directions", "[features]", D2,
                   D3, D4, D5, D6) {
  constexpr int N = TestType::value;
  // A generic simplex: no two faces are parallel, so every k-face has its own direction space.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nd;
  std::vector<Vec<N>> p;
  for (int i = 0; i <= N; ++i) p.push_back(Vec<N>::NullaryExpr([&] { return nd(rng); }));
  const ConvexFeatures<N> f = convex_features<N>(convex_hull<N>(p));
  REQUIRE(int(f.facets.size()) == N + 1);
  for (const auto& facet : f.facets) {
    CHECK(int(facet.vertices.size()) == N);
    CHECK(int(facet.neighbours.size()) == N);
  }
  for (int k = 1; k <= N - 2; ++k) {
    CHECK((long long)f.directions[k].size() == binomial(N + 1, k + 1));
    for (const auto& d : f.directions[k]) {  // orthonormal bases
      REQUIRE(int(d.basis.size()) == k);
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) CHECK(d.basis[i].dot(d.basis[j]) == Approx(i == j ? 1.0 : 0.0).margin(1e-12));
    }
  }
}
