// GJK and EPA timings (see bench/README.md, "GJK and EPA"):
//   BM_GjkSeparated<N>    gjk() on separated pairs of rotated boxes (distance and closest points)
//   BM_GjkOverlapping<N>  gjk() on overlapping pairs (stops at the first simplex enclosing the origin)
//   BM_GjkEpa<N>          gjk() then epa() on the overlapping pairs (one reused EpaWorkspace)
// Boxes are given as support functions c + R (h .* sign(R^T d)) with R precomputed, random half extents in
// [0.2, 1.2] and random orientations. Each iteration runs through kPairs pairs; items = pairs, so
// items_per_second is pairs per second and "time_per_pair" its inverse. Counters also give the mean
// number of GJK / EPA iterations per pair.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "wedge/collision/detail/epa.hpp"
#include "wedge/collision/detail/gjk.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"

namespace {

using namespace wedge;

constexpr int kPairs = 1024;

template <int N>
struct BoxSupport {
  Vec<N> centre;
  Mat<N> rotation;
  Vec<N> half;
  Vec<N> operator()(const Vec<N>& d) const {
    const Vec<N> local = rotation.transpose() * d;
    Vec<N> p;
    for (int i = 0; i < N; ++i) p[i] = local[i] >= 0.0 ? half[i] : -half[i];
    return centre + rotation * p;
  }
};

// Pairs whose centres are `spacing` times the sum of the circumradii apart along a random direction:
// > 1 separates them for sure, small values make them overlap for sure.
template <int N>
std::vector<std::pair<BoxSupport<N>, BoxSupport<N>>> make_pairs(double spacing, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), side(0.2, 1.2);
  std::normal_distribution<double> nd;
  const auto box = [&]() {
    BoxSupport<N> b;
    Bivector<N> biv;
    for (int i = 0; i < kBiv<N>; ++i) biv[i] = 2.0 * u(rng);
    b.rotation = to_matrix(exp<N>(biv));
    for (int i = 0; i < N; ++i) b.half[i] = side(rng);
    for (int i = 0; i < N; ++i) b.centre[i] = u(rng);
    return b;
  };
  std::vector<std::pair<BoxSupport<N>, BoxSupport<N>>> pairs;
  for (int k = 0; k < kPairs; ++k) {
    BoxSupport<N> a = box(), b = box();
    Vec<N> dir;
    for (int i = 0; i < N; ++i) dir[i] = nd(rng);
    b.centre = a.centre + spacing * (a.half.norm() + b.half.norm()) * dir.normalized();
    pairs.emplace_back(a, b);
  }
  return pairs;
}

void set_rates(benchmark::State& state, double gjk_iterations, double epa_iterations) {
  const double items = double(state.iterations()) * kPairs;
  state.SetItemsProcessed(std::int64_t(items));
  state.counters["time_per_pair"] = benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["gjk_iterations"] = gjk_iterations / items;
  if (epa_iterations > 0) state.counters["epa_iterations"] = epa_iterations / items;
}

// spacing 1.05: separated pairs (distance and closest points); 0.1: overlapping pairs (GJK stops at the
// first simplex around the origin).
template <int N>
void gjk_pairs(benchmark::State& state, double spacing, unsigned seed) {
  const auto pairs = make_pairs<N>(spacing, seed);
  double iterations = 0;
  for (auto _ : state)
    for (const auto& [a, b] : pairs) {
      const auto r = gjk<N>(a, b, Vec<N>(b.centre - a.centre));
      iterations += r.iterations;
      benchmark::DoNotOptimize(r.distance);
    }
  set_rates(state, iterations, 0);
}
template <int N>
void BM_GjkSeparated(benchmark::State& state) {
  gjk_pairs<N>(state, 1.05, 42 + N);
}
template <int N>
void BM_GjkOverlapping(benchmark::State& state) {
  gjk_pairs<N>(state, 0.1, 4242 + N);
}

template <int N>
void BM_GjkEpa(benchmark::State& state) {
  const auto pairs = make_pairs<N>(0.1, 4242 + N);
  EpaWorkspace<N> ws;
  double gjk_iterations = 0, epa_iterations = 0;
  for (auto _ : state)
    for (const auto& [a, b] : pairs) {
      const auto g = gjk<N>(a, b, Vec<N>(b.centre - a.centre));
      gjk_iterations += g.iterations;
      const auto r = epa<N>(a, b, g.simplex, {}, ws);
      epa_iterations += r.iterations;
      benchmark::DoNotOptimize(r.depth);
    }
  set_rates(state, gjk_iterations, epa_iterations);
}

BENCHMARK_TEMPLATE(BM_GjkSeparated, 3);
BENCHMARK_TEMPLATE(BM_GjkSeparated, 4);
BENCHMARK_TEMPLATE(BM_GjkOverlapping, 3);
BENCHMARK_TEMPLATE(BM_GjkOverlapping, 4);
BENCHMARK_TEMPLATE(BM_GjkEpa, 3);
BENCHMARK_TEMPLATE(BM_GjkEpa, 4);
// The other dimensions, for the record.
BENCHMARK_TEMPLATE(BM_GjkSeparated, 2);
BENCHMARK_TEMPLATE(BM_GjkSeparated, 5);
BENCHMARK_TEMPLATE(BM_GjkSeparated, 6);
BENCHMARK_TEMPLATE(BM_GjkOverlapping, 2);
BENCHMARK_TEMPLATE(BM_GjkOverlapping, 5);
BENCHMARK_TEMPLATE(BM_GjkOverlapping, 6);
BENCHMARK_TEMPLATE(BM_GjkEpa, 2);
BENCHMARK_TEMPLATE(BM_GjkEpa, 5);
BENCHMARK_TEMPLATE(BM_GjkEpa, 6);

}  // namespace

BENCHMARK_MAIN();
