// Broad-phase timings (see bench/README.md, "Broad phase"):
//   BM_BroadPhaseUpdate<N>/n/s  one broad-phase update of n moving bodies: every proxy gets its new box
//                             and displacement (move_proxy), then update_pairs; time per update and per
//                             body. s: the largest step per axis in mm (2: a pile settling, 20: a pile
//                             being stirred, where some bodies leave their fat boxes every update)
//   BM_BroadPhaseBuild<N>/n   n proxies created in an empty broad phase, then the first update_pairs
//                             (every proxy queries): the cost of loading a scene
//   BM_BruteForcePairs<N>/n   the quadratic baseline: every pair of the same fat boxes tested
// The scene is a pile: boxes of half-extent 0.3..0.5 m, centres uniform in a cube sized so that each
// body's fat box overlaps about 4 others; each update moves every body by a random step of up to s mm
// per axis (s = 2: 0.24 m/s at 120 Hz) with a pull of 5% of its offset back to its rest position, so the
// pile jitters in place (stationary spread 1.8 s mm per axis) instead of diffusing.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "wedge/collision/detail/broadphase.hpp"

namespace {

using namespace wedge;

template <int N>
struct Pile {
  std::vector<Vec<N>> rest, offset, half;
  explicit Pile(int n, std::uint64_t seed = 1) {
    // Fat boxes (side ~0.9 m) overlap if the centres are within ~0.9 m on every axis: 1.8^N of volume;
    // side^N = 1.8^N n / 4 gives about 4 neighbours per body.
    const double side = std::pow(std::pow(1.8, N) * n / 4.0, 1.0 / N);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(-side / 2, side / 2), size(0.3, 0.5);
    for (int k = 0; k < n; ++k) {
      Vec<N> c, h;
      for (int i = 0; i < N; ++i) {
        c[i] = pos(rng);
        h[i] = size(rng);
      }
      rest.push_back(c);
      half.push_back(h);
      offset.push_back(Vec<N>::Zero());
    }
  }
  Aabb<N> box(int k) const { return Aabb<N>::from_center(rest[k] + offset[k], half[k]); }
};

template <int N>
void BM_BroadPhaseUpdate(benchmark::State& state) {
  const int n = int(state.range(0));
  Pile<N> pile(n);
  BroadPhase<N> bp;
  std::vector<int> proxy;
  for (int k = 0; k < n; ++k) proxy.push_back(bp.create_proxy(pile.box(k), std::uint32_t(k)));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  bp.update_pairs(pairs);
  std::mt19937_64 rng(2);
  const double s = 1e-3 * double(state.range(1));
  std::uniform_real_distribution<double> step(-s, s);
  std::vector<Vec<N>> displacement(n);
  auto prepare = [&] {
    for (int k = 0; k < n; ++k) {
      for (int i = 0; i < N; ++i) displacement[k][i] = step(rng) - 0.05 * pile.offset[k][i];
      pile.offset[k] += displacement[k];
    }
  };
  // Warm up: let the jitter reach its stationary spread and the buffers their size.
  for (int w = 0; w < 200; ++w) {
    prepare();
    for (int k = 0; k < n; ++k) bp.move_proxy(proxy[k], pile.box(k), displacement[k]);
    bp.update_pairs(pairs);
  }
  double queried = 0.0, tests = 0.0, pair_count = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    prepare();  // the random motion is the simulation's work, not the broad phase's
    state.ResumeTiming();
    for (int k = 0; k < n; ++k) bp.move_proxy(proxy[k], pile.box(k), displacement[k]);
    bp.update_pairs(pairs);
    benchmark::DoNotOptimize(pairs.data());
    queried += bp.queried_proxies();
    tests += double(bp.node_overlap_tests());
    pair_count += double(pairs.size());
  }
  const double it = double(state.iterations());
  state.SetItemsProcessed(std::int64_t(it * n));
  state.counters["time_per_body"] = benchmark::Counter(it * n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["reinserted_fraction"] = queried / it / n;
  state.counters["node_tests"] = tests / it;
  state.counters["pairs"] = pair_count / it;
}

template <int N>
void BM_BroadPhaseBuild(benchmark::State& state) {
  const int n = int(state.range(0));
  const Pile<N> pile(n);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  double tests = 0.0;
  for (auto _ : state) {
    BroadPhase<N> bp;
    for (int k = 0; k < n; ++k) bp.create_proxy(pile.box(k), std::uint32_t(k));
    bp.update_pairs(pairs);
    benchmark::DoNotOptimize(pairs.data());
    tests += double(bp.node_overlap_tests());
  }
  const double it = double(state.iterations());
  state.SetItemsProcessed(std::int64_t(it * n));
  state.counters["time_per_body"] = benchmark::Counter(it * n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["node_tests"] = tests / it;
  state.counters["pairs"] = double(pairs.size());
}

template <int N>
void BM_BruteForcePairs(benchmark::State& state) {
  const int n = int(state.range(0));
  const Pile<N> pile(n);
  std::vector<Aabb<N>> fat;
  for (int k = 0; k < n; ++k) fat.push_back(fattened(pile.box(k), BroadPhaseSettings{}.margin));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (auto _ : state) {
    pairs.clear();
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        if (overlaps(fat[a], fat[b])) pairs.emplace_back(std::uint32_t(a), std::uint32_t(b));
    benchmark::DoNotOptimize(pairs.data());
  }
  const double it = double(state.iterations());
  state.SetItemsProcessed(std::int64_t(it * n));
  state.counters["time_per_body"] = benchmark::Counter(it * n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["pairs"] = double(pairs.size());
}

}  // namespace

BENCHMARK_TEMPLATE(BM_BroadPhaseUpdate, 3)->ArgsProduct({{1000, 10000}, {2, 20}})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_BroadPhaseUpdate, 4)->ArgsProduct({{1000, 10000}, {2, 20}})->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_BroadPhaseBuild, 3)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_BroadPhaseBuild, 4)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_BruteForcePairs, 4)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
