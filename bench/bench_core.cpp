// Core timings (see bench/README.md for results):
//   BM_WorldStep<N>       one World<N>::step of 1000 free tumbling boxes with gravity, per body (default
//                         settings: implicit midpoint gyroscopic step, rotor repair every step)
//   BM_WorldStepEuler<N>  the same with the paper's implicit Euler gyroscopic step (one Newton step)
//   BM_Exp<N>             exp of a sub-step's turn (components in [-0.01, 0.01]): the closed forms up to 5D, the
//                         invariants' power series in 6D (exp_three_planes, exp_log.hpp)
//   BM_ExpByDecomposition<N>  the same by the eigenvector decomposition of every plane
//   BM_*Compose<N>        Rotor * Rotor vs Eigen N x N matrix product (vs quaternion product in 3D)
//   BM_*Apply<N>          rotor sandwich R x ~R vs matrix-vector product M x with M precomputed
//   BM_RotorToMatrixApply to_matrix(R) then M x, i.e. rotating one vector starting from a stored rotor
//   BM_QuaternionApply    Eigen::Quaterniond * Vector3d (3D only)
// Every rotor/matrix benchmark works through arrays of kOps independent inputs per iteration, writes every
// result to an output array, and reports items (= single operations) per second; "time_per_op" /
// "time_per_body" is the inverse rate in nanoseconds.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <array>
#include <random>
#include <vector>

#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/world.hpp"

namespace {

using namespace wedge;

constexpr int kOps = 1024;     // independent operations per benchmark iteration
constexpr int kBodies = 1000;  // bodies per world

template <int N>
Vec<N> random_vec(std::mt19937_64& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Vec<N> v;
  for (int i = 0; i < N; ++i) v[i] = u(rng);
  return v;
}
template <int N>
Bivector<N> random_bivector(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Bivector<N> b;
  for (int i = 0; i < kBiv<N>; ++i) b[i] = u(rng);
  return b;
}
// A random rotation: exp of a random bivector with components in [-2, 2] (general double/triple
// rotations from 4D on).
template <int N>
Rotor<N> random_rotor(std::mt19937_64& rng) {
  return exp<N>(random_bivector<N>(rng, 2.0));
}

// Counters: items/s from SetItemsProcessed, plus its inverse, the CPU time per item (an inverted rate
// counter: seconds in the JSON, shown with an SI prefix on the console, e.g. "3.4ns").
void set_per_item(benchmark::State& state, std::int64_t items_per_iteration, const char* name) {
  const double items = double(state.iterations()) * double(items_per_iteration);
  state.SetItemsProcessed(std::int64_t(items));
  state.counters[name] = benchmark::Counter(items, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// ------------------------------------------------------------------ World::step
// 1000 dynamic boxes with random sides in [0.2, 2], random orientation (so the world inertia is a full
// k x k matrix although the body inertia is diagonal), random velocity and angular velocity in
// [-5, 5] rad/s per component, gravity on, default settings (gyroscopic term, rotor repair every step).
// No contacts: this is the cost of the integrator alone.
template <int N>
void world_step(benchmark::State& state, bool implicit_euler) {
  std::mt19937_64 rng(1234 + N);
  WorldSettings<N> settings;
  if (implicit_euler) settings.gyroscopic_method = GyroscopicMethod::ImplicitEuler;
  settings.gravity = Vec<N>::Zero();
  settings.gravity[1] = -9.81;
  World<N> world(settings);
  std::uniform_real_distribution<double> side(0.2, 2.0);
  for (int i = 0; i < kBodies; ++i) {
    BodyDef<N> def;
    std::array<double, N> a{};
    for (double& s : a) s = side(rng);
    def.mass = 1.0;
    def.inertia = BivMat<N>::Zero();
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) {
        const int k = Bivector<N>::index(p, q);
        def.inertia(k, k) = def.mass * (a[p] * a[p] + a[q] * a[q]) / 12.0;
      }
    def.position = random_vec<N>(rng, 100.0);
    def.rotor = random_rotor<N>(rng);
    def.velocity = random_vec<N>(rng, 1.0);
    def.angular_velocity = random_bivector<N>(rng, 5.0);
    world.add_body(def);
  }
  const double h = 1.0 / 120.0;
  for (auto _ : state) {
    world.step(h);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(world.state_hash());
  set_per_item(state, kBodies, "time_per_body");
}
template <int N>
void BM_WorldStep(benchmark::State& state) {
  world_step<N>(state, false);  // World's default gyroscopic method
}
template <int N>
void BM_WorldStepEuler(benchmark::State& state) {
  world_step<N>(state, true);
}

// ------------------------------------------------------------------ exp
template <int N, bool kDecomposition>
void exp_of_turns(benchmark::State& state) {
  std::mt19937_64 rng(77 + N);
  std::vector<Bivector<N>> b;
  for (int i = 0; i < kOps; ++i) b.push_back(random_bivector<N>(rng, 0.01));
  std::vector<Rotor<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i] = kDecomposition ? exp_by_decomposition(b[i]) : exp(b[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
template <int N>
void BM_Exp(benchmark::State& state) {
  exp_of_turns<N, false>(state);
}
template <int N>
void BM_ExpByDecomposition(benchmark::State& state) {
  exp_of_turns<N, true>(state);
}

// ------------------------------------------------------------------ rotor vs matrix
template <int N>
struct Inputs {
  std::vector<Rotor<N>> ra, rb;
  std::vector<Mat<N>> ma, mb;
  std::vector<Vec<N>> x;
  explicit Inputs(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < kOps; ++i) {
      ra.push_back(random_rotor<N>(rng));
      rb.push_back(random_rotor<N>(rng));
      ma.push_back(to_matrix(ra.back()));
      mb.push_back(to_matrix(rb.back()));
      x.push_back(random_vec<N>(rng));
    }
  }
};

template <int N>
void BM_RotorCompose(benchmark::State& state) {
  const Inputs<N> in(42);
  std::vector<Rotor<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i] = in.ra[i] * in.rb[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
template <int N>
void BM_MatrixCompose(benchmark::State& state) {
  const Inputs<N> in(42);
  std::vector<Mat<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i].noalias() = in.ma[i] * in.mb[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
template <int N>
void BM_RotorApply(benchmark::State& state) {  // sandwich R x ~R
  const Inputs<N> in(43);
  std::vector<Vec<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i] = rotate(in.ra[i], in.x[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
template <int N>
void BM_MatrixApply(benchmark::State& state) {  // M x, M precomputed
  const Inputs<N> in(43);
  std::vector<Vec<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i].noalias() = in.ma[i] * in.x[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
template <int N>
void BM_RotorToMatrixApply(benchmark::State& state) {  // to_matrix(R), then M x
  const Inputs<N> in(43);
  std::vector<Vec<N>> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i].noalias() = to_matrix(in.ra[i]) * in.x[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}

// 3D only: Eigen's unit quaternion, built from the same rotations.
struct QuatInputs {
  std::vector<Eigen::Quaterniond> qa, qb;
  std::vector<Eigen::Vector3d> x;
  explicit QuatInputs(std::uint64_t seed) {
    const Inputs<3> in(seed);
    for (int i = 0; i < kOps; ++i) {
      qa.emplace_back(in.ma[i]);
      qb.emplace_back(in.mb[i]);
      x.push_back(in.x[i]);
    }
  }
};
void BM_QuaternionCompose(benchmark::State& state) {
  const QuatInputs in(42);
  std::vector<Eigen::Quaterniond> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i] = in.qa[i] * in.qb[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}
void BM_QuaternionApply(benchmark::State& state) {
  const QuatInputs in(43);
  std::vector<Eigen::Vector3d> out(kOps);
  for (auto _ : state) {
    for (int i = 0; i < kOps; ++i) out[i] = in.qa[i] * in.x[i];
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, kOps, "time_per_op");
}

}  // namespace

BENCHMARK_TEMPLATE(BM_WorldStep, 2);
BENCHMARK_TEMPLATE(BM_WorldStep, 3);
BENCHMARK_TEMPLATE(BM_WorldStep, 4);
BENCHMARK_TEMPLATE(BM_WorldStep, 5);
BENCHMARK_TEMPLATE(BM_WorldStep, 6);
BENCHMARK_TEMPLATE(BM_WorldStepEuler, 3);
BENCHMARK_TEMPLATE(BM_WorldStepEuler, 4);
BENCHMARK_TEMPLATE(BM_Exp, 4);
BENCHMARK_TEMPLATE(BM_Exp, 5);
BENCHMARK_TEMPLATE(BM_Exp, 6);
BENCHMARK_TEMPLATE(BM_ExpByDecomposition, 4);
BENCHMARK_TEMPLATE(BM_ExpByDecomposition, 5);
BENCHMARK_TEMPLATE(BM_ExpByDecomposition, 6);

BENCHMARK_TEMPLATE(BM_RotorCompose, 3);
BENCHMARK_TEMPLATE(BM_MatrixCompose, 3);
BENCHMARK(BM_QuaternionCompose);
BENCHMARK_TEMPLATE(BM_RotorApply, 3);
BENCHMARK_TEMPLATE(BM_MatrixApply, 3);
BENCHMARK_TEMPLATE(BM_RotorToMatrixApply, 3);
BENCHMARK(BM_QuaternionApply);

BENCHMARK_TEMPLATE(BM_RotorCompose, 4);
BENCHMARK_TEMPLATE(BM_MatrixCompose, 4);
BENCHMARK_TEMPLATE(BM_RotorApply, 4);
BENCHMARK_TEMPLATE(BM_MatrixApply, 4);
BENCHMARK_TEMPLATE(BM_RotorToMatrixApply, 4);

BENCHMARK_MAIN();
