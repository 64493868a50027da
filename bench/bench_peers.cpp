// Wedge beside today's leading engines, in one process (bench/README.md, "Peers: Box2D v3 and Jolt"):
//   Pyramid2D_{Wedge,Box2Dv3}/<rows>   Box2D's pyramid, 20, 40 and 100 rows (210, 820 and 5,050 boxes)
//   Pile3D_{Wedge,Jolt}                1,000 boxes dropped in a grid onto the ground (as wedge_bench_contact)
//   JoltPyramid_{Wedge,Jolt}           Jolt's PerformanceTest pyramid, 1,240 boxes in 15 staggered layers
//   JointGrid_{Wedge,Box2Dv3}          Box2D v3's joint_grid: 100 x 100 disks on 19,800 revolute joints,
//                                      at Box2D's joint stiffness and sub-steps (60 Hz, 4)
// Built only when a peer's source folder is given to CMake (WEDGE_BOX2D_V3_DIR, WEDGE_JOLT_DIR); each
// engine runs with its own defaults and sleeping off, one thread; the .../threads:2 runs give each engine
// both cores (Wedge: WorldSettings::workers; Box2D v3: its scheduler; Jolt: its thread pool) and report
// wall time, since CPU time would count both threads. One benchmark iteration is one step at
// 60 Hz; each run first builds the scene and steps it untimed (warm-up), then times a fixed number of
// steps. Run with --benchmark_enable_random_interleaving=true so that the engines' repetitions alternate.
//
// Counters, so that an engine that is fast but lets its scene fall over shows up as such (after the
// warm-up and the timed steps):
//   max_speed  m/s, the fastest box's centre        moving  boxes faster than 0.1 m/s
//   top_dy     m, height of the last box (a pyramid's top) minus its initial height
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <vector>

#include "wedge_scenes.hpp"
#if WEDGE_PEER_BOX2D_V3
#include "peer_box2d_v3.hpp"
#endif
#if WEDGE_PEER_JOLT
#include "peer_jolt.hpp"
#endif

namespace {

using namespace wedge;
using namespace wedge::bench;

constexpr double kMoving = 0.1;  // m/s

struct Run {
  int warmup = 0, timed = 0;
};
// The pyramids start at rest: 2 s settle untimed, 2 s timed. The pile falls for about 2 s and heaps up:
// 10 s untimed. Jolt's pyramid drops 0.5 m per layer: 2 s untimed.
// The joint grid falls from its straight lines and swings: 1 s untimed, 2 s timed.
constexpr Run kPyramid{120, 120}, kPile{600, 300}, kJoltPyramid{120, 300}, kJointGrid{60, 120};
constexpr int kGrid = 100;  // disks per side (Box2D v3's joint_grid)

// Warm-up, then the timed steps, then the counters. `Scene` has step(), max_speed(), moving(v), height(k),
// count() (the peers' wrappers; Wedge's through WedgeScene).
template <typename Scene>
void run(benchmark::State& state, Scene& scene, const Run& r) {
  const double top0 = scene.height(scene.count() - 1);
  for (int i = 0; i < r.warmup; ++i) scene.step();
  for (auto _ : state) scene.step();
  state.counters["max_speed"] = scene.max_speed();
  state.counters["moving"] = scene.moving(kMoving);
  state.counters["top_dy"] = scene.height(scene.count() - 1) - top0;
}

// A Wedge world behind the peers' interface: its dynamic bodies in order.
template <int N>
class WedgeScene {
 public:
  explicit WedgeScene(World<N> w, int workers = 1, int substeps = 0) : world_(std::move(w)) {
    world_.update_settings([&](auto& s) {
      s.workers = workers;
      if (substeps > 0) s.contact.substeps = substeps;
    });
    for (int i = 0; i < world_.body_count(); ++i)
      if (world_.bodies()[std::size_t(i)].is_dynamic()) boxes_.push_back(BodyId{std::uint32_t(i)});
  }
  void step() { world_.step(kDt); }
  double max_speed() const { return wedge::bench::max_speed(world_); }
  int moving(double v) const { return moving_count(world_, v); }
  double height(std::size_t k) const { return world_.body(boxes_[k]).center[1]; }
  std::size_t count() const { return boxes_.size(); }
  const World<N>& world() const { return world_; }

 private:
  World<N> world_;
  std::vector<BodyId> boxes_;
};

// Each scene with 1 and 2 threads: state.range(1) (Pyramid2D) or range(0) is the thread count.
void Pyramid2D_Wedge(benchmark::State& state) {
  WedgeScene<2> scene(peers_pyramid(int(state.range(0))), int(state.range(1)));
  run(state, scene, kPyramid);
}
void Pyramid2D_Wedge_substeps4(benchmark::State& state) {
  WedgeScene<2> scene(peers_pyramid(int(state.range(0))), 1, 4);
  run(state, scene, kPyramid);
}
void Pile3D_Wedge(benchmark::State& state) {
  WedgeScene<3> scene(wedge_pile<3>(1000, false), int(state.range(0)));
  run(state, scene, kPile);
}
void JoltPyramid_Wedge(benchmark::State& state) {
  WedgeScene<3> scene(wedge_jolt_pyramid(), int(state.range(0)));
  run(state, scene, kJoltPyramid);
}
void JointGrid_Wedge(benchmark::State& state) {
  WedgeScene<2> scene(joint_grid(kGrid));
  run(state, scene, kJointGrid);
}
// (8 sub-steps: where Wedge's grid holds; docs/joints.md, "Heavy loads on light bodies")
void JointGrid_Wedge_substeps8(benchmark::State& state) {
  WedgeScene<2> scene(joint_grid(kGrid, 8));
  run(state, scene, kJointGrid);
}
// A 2D pyramid benchmark at 20, 40 and 100 rows, one thread.
template <typename Fn>
void add_rows(const char* name, Fn fn) {
  benchmark::RegisterBenchmark(name, fn)
      ->ArgName("rows")
      ->Arg(20)
      ->Arg(40)
      ->Arg(100)
      ->Iterations(kPyramid.timed)
      ->Unit(benchmark::kMillisecond);
}
// Registers a benchmark once per thread count, the 2-thread run on wall time.
template <typename Fn>
void add(const char* name, Fn fn, int timed, std::vector<std::int64_t> rows = {}) {
  for (const int threads : {1, 2}) {
    benchmark::internal::Benchmark* b = benchmark::RegisterBenchmark(name, fn);
    if (rows.empty()) {
      b->ArgName("threads")->Arg(threads);
    } else {
      b->ArgNames({"rows", "threads"});
      for (const std::int64_t r : rows) b->Args({r, threads});
    }
    b->Iterations(timed)->Unit(benchmark::kMillisecond);
    if (threads > 1) b->UseRealTime();
  }
}
const bool registered_wedge = [] {
  add("Pyramid2D_Wedge", Pyramid2D_Wedge, kPyramid.timed, {20, 40, 100});
  add_rows("Pyramid2D_Wedge_substeps4", Pyramid2D_Wedge_substeps4);
  add("Pile3D_Wedge", Pile3D_Wedge, kPile.timed);
  add("JoltPyramid_Wedge", JoltPyramid_Wedge, kJoltPyramid.timed);
  using Fn = void (*)(benchmark::State&);
  for (const auto& [name, fn] : {std::pair<const char*, Fn>{"JointGrid_Wedge", JointGrid_Wedge},
                                 std::pair<const char*, Fn>{"JointGrid_Wedge_substeps8", JointGrid_Wedge_substeps8}})
    benchmark::RegisterBenchmark(name, fn)->Iterations(kJointGrid.timed)->Unit(benchmark::kMillisecond);
  return true;
}();

#if WEDGE_PEER_BOX2D_V3
void Pyramid2D_Box2Dv3(benchmark::State& state) {
  Box2DV3Scene scene(peers_pyramid(int(state.range(0))), false, int(state.range(1)));
  run(state, scene, kPyramid);
}
// Box2D v3 at Wedge's defaults, 8 sub-steps and a 60 Hz contact spring: the stiffness that keeps the
// 100-row pyramid's top within issue 15's 0.25 m (at its own 4 sub-steps and 30 Hz it sinks 0.72 m).
void Pyramid2D_Box2Dv3_substeps8_60Hz(benchmark::State& state) {
  Box2DV3Scene scene(peers_pyramid(int(state.range(0))), false, 1, 8, 60.0f);
  run(state, scene, kPyramid);
}
void JointGrid_Box2Dv3(benchmark::State& state) {
  Box2DV3JointGrid scene(kGrid);
  run(state, scene, kJointGrid);
}
const bool registered_box2d = [] {
  benchmark::RegisterBenchmark("JointGrid_Box2Dv3", JointGrid_Box2Dv3)->Iterations(kJointGrid.timed)->Unit(benchmark::kMillisecond);
  add("Pyramid2D_Box2Dv3", Pyramid2D_Box2Dv3, kPyramid.timed, {20, 40, 100});
  add_rows("Pyramid2D_Box2Dv3_substeps8_60Hz", Pyramid2D_Box2Dv3_substeps8_60Hz);
  return true;
}();
#endif

#if WEDGE_PEER_JOLT
// The dynamic bodies of a Wedge 3D world as Jolt boxes.
std::vector<BoxPose> poses(const World<3>& w) {
  std::vector<BoxPose> out;
  for (const Body<3>& b : w.bodies()) {
    if (!b.is_dynamic()) continue;
    const Eigen::Quaterniond q(to_matrix(b.rotor));
    out.push_back({{b.center[0], b.center[1], b.center[2]}, {q.w(), q.x(), q.y(), q.z()}});
  }
  return out;
}
JoltSettings jolt_settings(double half, int threads) {
  return {.half = half, .density = kDensity, .friction = kFriction, .gravity = kGravity, .dt = kDt, .sleep = false,
          .threads = threads};
}
void Pile3D_Jolt(benchmark::State& state) {
  JoltScene scene(poses(wedge_pile<3>(1000, false)), jolt_settings(kHalf, int(state.range(0))));
  run(state, scene, kPile);
}
void JoltPyramid_Jolt(benchmark::State& state) {
  JoltScene scene(poses(wedge_jolt_pyramid()), jolt_settings(1.0, int(state.range(0))));
  run(state, scene, kJoltPyramid);
}
const bool registered_jolt = [] {
  add("Pile3D_Jolt", Pile3D_Jolt, kPile.timed);
  add("JoltPyramid_Jolt", JoltPyramid_Jolt, kJoltPyramid.timed);
  return true;
}();
#endif

}  // namespace

BENCHMARK_MAIN();
