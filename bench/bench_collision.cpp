// Narrow-phase timings through the public dispatch (wedge::collide): box-box SAT in 3D and 4D (separated
// and overlapping pairs, with their manifolds), a tesseract on the ground, polytope-polytope SAT, and
// round product - box through GJK/EPA. Pairs per second = items_per_second.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "wedge/collision/narrow_phase.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"

using namespace wedge;

namespace {

template <int N>
struct Pair {
  Transform<N> ta, tb;
};

// 256 random placements of b around a at the given centre distance (relative to a unit-ish size).
template <int N>
std::vector<Pair<N>> placements(double distance, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> nd;
  std::vector<Pair<N>> out;
  for (int i = 0; i < 256; ++i) {
    Bivector<N> ba, bb;
    for (int k = 0; k < kBiv<N>; ++k) ba[k] = nd(rng), bb[k] = nd(rng);
    Vec<N> dir = Vec<N>::NullaryExpr([&] { return nd(rng); }).normalized();
    out.push_back({{Vec<N>::Zero(), to_matrix(exp(ba))}, {Vec<N>(distance * dir), to_matrix(exp(bb))}});
  }
  return out;
}

template <int N>
void run_pairs(benchmark::State& state, const Shape<N>& a, const Shape<N>& b, double distance) {
  const auto pairs = placements<N>(distance, 7);
  std::size_t i = 0;
  int hits = 0;
  for (auto _ : state) {
    const Pair<N>& p = pairs[i++ & 255];
    const Manifold<N> m = collide(a, p.ta, b, p.tb);
    hits += m.intersecting;
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}

template <int N>
void BM_BoxBox(benchmark::State& state) {
  const Shape<N> box = Shape<N>::box(Vec<N>::Constant(0.5));
  // range(0): centre distance in cm: 80 cm mostly overlapping, 300 cm always apart.
  run_pairs<N>(state, box, box, state.range(0) / 100.0);
}

template <int N>
void BM_PolytopeBox(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> nd;
  std::vector<Vec<N>> pts;
  for (int i = 0; i < N + 6; ++i) pts.push_back(Vec<N>::NullaryExpr([&] { return 0.5 * nd(rng); }));
  const Shape<N> poly = Shape<N>::polytope(pts);
  run_pairs<N>(state, poly, Shape<N>::box(Vec<N>::Constant(0.5)), state.range(0) / 100.0);
}

template <int N>
void BM_RoundBox(benchmark::State& state) {  // GJK (+ EPA when overlapping)
  run_pairs<N>(state, Shape<N>::cylinder(0.5, 0.5), Shape<N>::box(Vec<N>::Constant(0.5)), state.range(0) / 100.0);
}

void BM_TesseractOnGround(benchmark::State& state) {
  const Shape<4> ground = Shape<4>::halfspace(Vec<4>::UnitY(), 0.0);
  const Shape<4> cube = Shape<4>::box(Vec<4>::Constant(0.5));
  const Transform<4> tg{}, tc{Vec<4>(0, 0.499, 0, 0), Mat<4>::Identity()};
  for (auto _ : state) benchmark::DoNotOptimize(collide(ground, tg, cube, tc));
  state.SetItemsProcessed(state.iterations());
}

// The case a contact solver sees most: one tesseract resting on another, turned a little within the
// contact plane (a face-to-face manifold of 8 points every query).
void BM_TesseractOnTesseract(benchmark::State& state) {
  const Shape<4> cube = Shape<4>::box(Vec<4>::Constant(0.5));
  Bivector<4> turn;
  turn[1] = 0.1;  // e02
  turn[5] = 0.05;  // e23
  const Transform<4> ta{}, tb{Vec<4>(0.05, 0.999, -0.03, 0.02), to_matrix(exp(turn))};
  int points = 0;
  for (auto _ : state) {
    const Manifold<4> m = collide(cube, ta, cube, tb);
    points = m.count;
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = points;
}

}  // namespace

BENCHMARK(BM_TesseractOnTesseract);
BENCHMARK(BM_BoxBox<3>)->Arg(80)->Arg(300);
BENCHMARK(BM_BoxBox<4>)->Arg(80)->Arg(300);
BENCHMARK(BM_PolytopeBox<3>)->Arg(80)->Arg(300);
BENCHMARK(BM_PolytopeBox<4>)->Arg(80)->Arg(300);
BENCHMARK(BM_RoundBox<3>)->Arg(80)->Arg(300);
BENCHMARK(BM_RoundBox<4>)->Arg(80)->Arg(300);
BENCHMARK(BM_TesseractOnGround);

BENCHMARK_MAIN();
