// The input layer's cost (docs/input.md): Interaction::before_step + after_step per step with one hand
// holding a body (the world step itself excluded, by manual timing), 2D-6D; and `wedge replay`'s work
// on the 4D toy table (scene + scripted grab session, 7.5 s of input) as a multiple of real time,
// headless: load, resample, apply, step, haptics, no output.
#include <benchmark/benchmark.h>

#include <chrono>

#include "wedge/scenes/scene.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/recordings/recording_source.hpp"
#include "wedge/mass.hpp"

using namespace wedge;

namespace {

template <int N>
void BM_InputPerStepAndHand(benchmark::State& state) {
  WorldSettings<N> s;
  s.gravity = Vec<N>::Zero();
  s.gravity[1] = -9.81;
  World<N> world(s);
  BodyDef<N> ground;
  ground.type = BodyType::Static;
  Vec<N> up = Vec<N>::Zero();
  up[1] = 1.0;
  ground.shape = std::make_shared<const Shape<N>>(Shape<N>::halfspace(up, 0.0));
  world.add_body(ground);
  for (int i = 0; i < 4; ++i) {
    BodyDef<N> d;
    const Vec<N> he = Vec<N>::Constant(0.1);
    d.shape = std::make_shared<const Shape<N>>(Shape<N>::box(he));
    const MassProperties<N> mp = box_mass_properties<N>(he, 500.0);
    d.mass = mp.mass;
    d.inertia = mp.inertia;
    d.position = 0.1 * up;
    d.position[0] = 0.3 * i;
    world.add_body(d);
  }
  input::Interaction<N> in(world, input::InteractionSettings<N>{});
  const double h = 1.0 / 120.0;
  std::int64_t k = 0;
  for (auto _ : state) {
    input::InputFrame f;
    f.t = double(k) * h;
    input::HandInput& hand = f.hands[1];
    hand.tracked = true;
    hand.position = Eigen::Vector3d(0.1 * std::sin(f.t), 0.15 + 0.05 * std::sin(3 * f.t), 0.0);
    hand.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * std::sin(f.t), Eigen::Vector3d::UnitZ()));
    hand.squeeze = 1.0;
    const auto t0 = std::chrono::steady_clock::now();
    in.before_step(f, h);
    const auto t1 = std::chrono::steady_clock::now();
    world.step(h);
    const auto t2 = std::chrono::steady_clock::now();
    in.after_step();
    const auto t3 = std::chrono::steady_clock::now();
    state.SetIterationTime(std::chrono::duration<double>((t1 - t0) + (t3 - t2)).count());
    ++k;
  }
  if (!in.held(1)) state.SkipWithError("the hand holds nothing");
}

void BM_ReplayToyTable(benchmark::State& state) {
  const std::string root = WEDGE_SOURCE_DIR;
  const scenes::Scene<4> scene = scenes::load_scene_file<4>(root + "/scenes/toy_table_4d.json");
  const std::string rec = root + "/recordings/scripted/toy_table_grab.jsonl";
  const recordings::Recording recording = recordings::read_recording(rec);
  double simulated = 0.0;
  for (auto _ : state) {
    World<4> world = scene.make_world("toy_table_4d.json");
    recordings::RecordingSource src({recording}, {rec});
    input::InteractionSettings<4> settings;
    settings.tracking.origin = scene.interaction.origin;
    input::Interaction<4> in(world, settings);
    const double h = scene.timestep;
    const std::int64_t steps = std::int64_t(std::ceil(src.duration() / h - 1e-9));
    for (std::int64_t k = 0; k < steps; ++k) {
      in.before_step(src.frame_at(double(k) * h), h);
      world.step(h);
      in.after_step();
    }
    benchmark::DoNotOptimize(world.state_hash());
    simulated += double(steps) * h;
  }
  state.counters["x_real_time"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_TEMPLATE(BM_InputPerStepAndHand, 2)->UseManualTime();
BENCHMARK_TEMPLATE(BM_InputPerStepAndHand, 3)->UseManualTime();
BENCHMARK_TEMPLATE(BM_InputPerStepAndHand, 4)->UseManualTime();
BENCHMARK_TEMPLATE(BM_InputPerStepAndHand, 5)->UseManualTime();
BENCHMARK_TEMPLATE(BM_InputPerStepAndHand, 6)->UseManualTime();
BENCHMARK(BM_ReplayToyTable)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
