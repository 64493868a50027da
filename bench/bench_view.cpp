// The viewer's frame budget without the GPU: physics (1/60 s of simulated time per frame) plus slicing
// every body to 3D, per frame, on the play scenes (issue 14's goal: under 2 ms together). Drawing is
// measured in the viewer itself (its panel), since it depends on the GL implementation.
#include <benchmark/benchmark.h>

#include <chrono>

#include "wedge/scenes/scene.hpp"
#include "wedge/slicing/world_slices.hpp"

using namespace wedge;

namespace {

template <int N>
void frame(benchmark::State& state, const char* name) {
  const std::string file = std::string(WEDGE_SOURCE_DIR) + "/scenes/" + name;
  const scenes::Scene<N> scene = scenes::load_scene_file<N>(file);
  World<N> world = scene.make_world(file);
  slicing::WorldSlices<N> slices(world, {}, int(state.range(0)));  // subdivisions: 8 is the viewer default in 4D  // the viewer's default tessellation
  std::vector<slicing::DisplayMesh<3>> meshes;
  const double h = scene.timestep;
  const int steps = std::max(1, int(std::lround((1.0 / 60.0) / h)));
  double physics = 0.0, slicing_time = 0.0;
  std::int64_t frames = 0;
  for (auto _ : state) {
    if (world.time() > 20.0) {  // keep the scene moving: start again (outside the timing)
      state.PauseTiming();
      world = scene.make_world(file);
      state.ResumeTiming();
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) world.step(h);
    const auto t1 = std::chrono::steady_clock::now();
    slices.slice(world, meshes);
    const auto t2 = std::chrono::steady_clock::now();
    physics += std::chrono::duration<double>(t1 - t0).count();
    slicing_time += std::chrono::duration<double>(t2 - t1).count();
    ++frames;
    benchmark::DoNotOptimize(meshes.data());
  }
  state.counters["physics_ms"] = 1e3 * physics / double(frames);
  state.counters["slicing_ms"] = 1e3 * slicing_time / double(frames);
}

void frame4(benchmark::State& state, const char* name) { frame<4>(state, name); }

}  // namespace

BENCHMARK_CAPTURE(frame4, toy_table_4d, "toy_table_4d.json")->Arg(8)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame4, fig1_stack_4d, "fig1_stack_4d.json")->Arg(8)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame4, fig2_duocylinder_4d, "fig2_duocylinder_4d.json")->Arg(8)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame4, fig3_dominoes_4d, "fig3_dominoes_4d.json")->Arg(8)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(frame4, fig4_spinning_4d, "fig4_spinning_4d.json")->Arg(8)->Arg(5)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
