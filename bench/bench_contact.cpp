// Contact timings, Wedge beside Box2D and Bullet (bench/README.md, "Contact"; run by bench/run_contact.sh):
//   Pyramid2D_{Wedge,Box2D}/sleep_{off,on}   a 20-row pyramid of 210 boxes on the ground (2D)
//   Pile3D_{Wedge,Bullet}/sleep_{off,on}     1,000 boxes dropped in a grid onto the ground (3D)
//   Pile4D_Wedge/<count>/sleep_{off,on}      100, 1,000 and 10,000 tesseracts dropped likewise (4D)
//   Pile4D_Wedge/1000/settled                the 1,000 pile with sleeping on after 30 s, once settled
//   .../continuous_off                       the same steps without the continuous-collision stage
//   PaperScene/<name>                        the paper's figure scenes, scenes/fig*_4d.json
//   Workers_HandOver                         one empty job handed to a second thread and back (wall time)
// One benchmark iteration is one step, so the time per iteration is the CPU time of one World::step (or
// one b2World::Step, one btDiscreteDynamicsWorld::stepSimulation). Each scene first runs a warm-up that
// is not timed (the same number of steps in both engines), then exactly the timed steps (fixed
// Iterations); the scenes and the settings the engines share are in contact_scenes.hpp. The Wedge worlds
// are warmed up once and copied for each repetition; the peers have no copy, so they are rebuilt and
// warmed up again (the same deterministic run each time).
//
// Counters (state at the start of the timed steps unless said otherwise):
//   awake    fraction of the dynamic bodies awake
//   moving   dynamic bodies whose centre moves faster than 0.1 m/s
//   top_dy   m, height of the pyramid's top box minus its initial height (the pyramid stands: |top_dy| is
//            small); top_dx likewise sideways; top_dy_end after the timed steps
//   pairs    pairs with contact points after the timed steps (Wedge: contacts(); Box2D: touching
//            b2Contacts; Bullet: manifolds holding points)
//   max_pen  m, deepest penetration of any contact point after the timed steps
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "contact_scenes.hpp"
#include "parallel/workers.hpp"
#include "wedge/scenes/scene.hpp"

namespace {

using namespace wedge;
using namespace wedge::bench;

// Step counts at 60 Hz. The pyramid starts at rest and settles within the warm-up (5 s). The piles fall
// for about 2 s and then heap up; 15 s of warm-up leave a few percent of the boxes moving in both
// engines (the "moving" counter). The 10,000-tesseract pile steps too slowly for that: see kBigPile*.
constexpr int kPyramidWarmup = 300, kPyramidTimed = 300;
constexpr int kPileWarmup = 900, kPileTimed = 300;
constexpr int kBigPileCount = 10000;
constexpr int kBigPileWarmup = 300, kBigPileTimed = 60;
// "Once settled": the 1,000-tesseract pile with sleeping on is stepped until every body is asleep, at
// most this long (when it falls asleep depends on rounding: 25-40 s in the solvers measured so far).
constexpr int kSettledMaxWarmup = 120 * 60;
constexpr int kSceneTimed = 600;  // paper scenes: the first 600 steps from the file's initial state
constexpr double kMovingSpeed = 0.1;  // m/s

// ------------------------------------------------------------------ measurements of a state

template <int N>
int moving_count(const World<N>& w) {
  return wedge::bench::moving_count(w, kMovingSpeed);
}
int moving_count(const Box2DScene& s) {
  int n = 0;
  for (const b2Body* b : s.boxes) n += b->GetLinearVelocity().Length() > kMovingSpeed ? 1 : 0;
  return n;
}
int moving_count(const BulletScene& s) {
  int n = 0;
  for (std::size_t i = 1; i < s.bodies.size(); ++i) n += s.bodies[i]->getLinearVelocity().length() > kMovingSpeed ? 1 : 0;
  return n;
}

template <int N>
double max_penetration(const World<N>& w) {
  double d = 0.0;
  for (const ContactInfo<N>& c : w.contacts())
    for (int k = 0; k < c.manifold.count; ++k) d = std::max(d, c.manifold.points[k].depth);
  return d;
}
double max_penetration(BulletScene& s) {
  double d = 0.0;
  btDispatcher* dispatcher = s.world.getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    for (int k = 0; k < manifold->getNumContacts(); ++k)
      d = std::max(d, -double(manifold->getContactPoint(k).getDistance()));
  }
  return d;
}

template <class Scene>
void set_start_counters(benchmark::State& state, const Scene& scene, int awake, int dynamic) {
  state.counters["awake"] = double(awake) / double(dynamic);
  state.counters["moving"] = moving_count(scene);
}

// ------------------------------------------------------------------ Wedge worlds, warmed up once

// Builds the world, runs `warmup` steps (or, with until_asleep, steps until no body is awake, at most
// `warmup`) and keeps it; each call returns the same settled state.
template <int N, class Make>
const World<N>& settled(const std::string& key, int warmup, Make&& make, bool until_asleep = false) {
  static std::map<std::string, World<N>> cache;
  auto it = cache.find(key);
  if (it == cache.end()) {
    World<N> w = make();
    for (int i = 0; i < warmup; ++i) {
      if (until_asleep && awake_count(w) == 0) break;
      w.step(kDt);
    }
    it = cache.emplace(key, std::move(w)).first;
  }
  return it->second;
}

template <int N>
int dynamic_count(const World<N>& w) {
  int n = 0;
  for (const Body<N>& b : w.bodies()) n += b.is_dynamic() ? 1 : 0;
  return n;
}

// Times `state.iterations()` steps of a copy of the settled world.
template <int N>
void time_wedge(benchmark::State& state, const World<N>& start, double h, int workers = 1, bool continuous = true) {
  World<N> w = start;
  w.update_settings([&](auto& s) { s.workers = workers; s.contact.continuous = continuous; });
  set_start_counters(state, w, awake_count(w), dynamic_count(w));
  for (auto _ : state) w.step(h);
  state.counters["pairs"] = double(w.contacts().size());
  state.counters["max_pen"] = max_penetration(w);
}

// ------------------------------------------------------------------ 1. 2D pyramid: Wedge and Box2D

constexpr int kPyramidRows = 20;  // 210 boxes

double top_angle(const World<2>& w, BodyId id) {
  const Mat<2> r = to_matrix(w.body(id).rotor);
  return std::atan2(r(1, 0), r(0, 0));
}

void Pyramid2D_Wedge(benchmark::State& state, bool sleep, int workers = 1, bool continuous = true) {
  const World<2> initial = wedge_pyramid(kPyramidRows, sleep);
  const World<2>& start = settled<2>(sleep ? "pyramid/on" : "pyramid/off", kPyramidWarmup,
                                     [&] { return wedge_pyramid(kPyramidRows, sleep); });
  const BodyId top{std::uint32_t(initial.body_count() - 1)};
  World<2> w = start;
  w.update_settings([&](auto& s) { s.workers = workers; s.contact.continuous = continuous; });
  set_start_counters(state, w, awake_count(w), dynamic_count(w));
  state.counters["top_dy"] = w.body(top).center[1] - initial.body(top).center[1];
  state.counters["top_dx"] = w.body(top).center[0] - initial.body(top).center[0];
  state.counters["top_angle"] = top_angle(w, top);
  for (auto _ : state) w.step(kDt);
  state.counters["top_dy_end"] = w.body(top).center[1] - initial.body(top).center[1];
  state.counters["pairs"] = double(w.contacts().size());
  state.counters["max_pen"] = max_penetration(w);
}

void Pyramid2D_Box2D(benchmark::State& state, bool sleep) {
  const World<2> layout = wedge_pyramid(kPyramidRows, sleep);
  Box2DScene scene(layout, sleep);
  const b2Body* top = scene.boxes.back();
  const b2Vec2 p0 = top->GetPosition();
  for (int i = 0; i < kPyramidWarmup; ++i) scene.step();
  set_start_counters(state, scene, scene.awake_count(), int(scene.boxes.size()));
  state.counters["top_dy"] = top->GetPosition().y - p0.y;
  state.counters["top_dx"] = top->GetPosition().x - p0.x;
  state.counters["top_angle"] = top->GetAngle();
  for (auto _ : state) scene.step();
  state.counters["top_dy_end"] = top->GetPosition().y - p0.y;
  int touching = 0;
  for (const b2Contact* c = scene.world->GetContactList(); c; c = c->GetNext()) touching += c->IsTouching() ? 1 : 0;
  state.counters["pairs"] = touching;
}

BENCHMARK_CAPTURE(Pyramid2D_Wedge, sleep_off, false)->Iterations(kPyramidTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pyramid2D_Box2D, sleep_off, false)->Iterations(kPyramidTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pyramid2D_Wedge, sleep_on, true)->Iterations(kPyramidTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pyramid2D_Box2D, sleep_on, true)->Iterations(kPyramidTimed)->Unit(benchmark::kMillisecond);
// The same steps without the continuous-collision stage (ContactSettings::continuous): what it costs.
BENCHMARK_CAPTURE(Pyramid2D_Wedge, sleep_off/continuous_off, false, 1, false)
    ->Iterations(kPyramidTimed)->Unit(benchmark::kMillisecond);
// Both cores (WorldSettings::workers = 2): wall time, since the process's CPU time counts both threads.
BENCHMARK_CAPTURE(Pyramid2D_Wedge, sleep_off/workers:2, false, 2)
    ->Iterations(kPyramidTimed)->UseRealTime()->Unit(benchmark::kMillisecond);

// ------------------------------------------------------------------ 2. 3D pile: Wedge and Bullet

constexpr int kPileCount = 1000;

template <int N>
const World<N>& settled_pile(int count, bool sleep, int warmup, bool until_asleep = false) {
  const std::string key = std::to_string(N) + "/" + std::to_string(count) + (sleep ? "/on/" : "/off/") +
                          std::to_string(warmup) + (until_asleep ? "/asleep" : "");
  return settled<N>(key, warmup, [&] { return wedge_pile<N>(count, sleep); }, until_asleep);
}

void Pile3D_Wedge(benchmark::State& state, bool sleep, int workers = 1, bool continuous = true) {
  time_wedge<3>(state, settled_pile<3>(kPileCount, sleep, kPileWarmup), kDt, workers, continuous);
}

void Pile3D_Bullet(benchmark::State& state, bool sleep) {
  const World<3> layout = wedge_pile<3>(kPileCount, sleep);
  BulletScene scene(layout, sleep);
  for (int i = 0; i < kPileWarmup; ++i) scene.step();
  set_start_counters(state, scene, scene.awake_count(), int(scene.bodies.size()) - 1);
  for (auto _ : state) scene.step();
  int touching = 0;
  for (int m = 0; m < scene.dispatcher.getNumManifolds(); ++m)
    touching += scene.dispatcher.getManifoldByIndexInternal(m)->getNumContacts() > 0 ? 1 : 0;
  state.counters["pairs"] = touching;
  state.counters["max_pen"] = max_penetration(scene);
}

BENCHMARK_CAPTURE(Pile3D_Wedge, sleep_off, false)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile3D_Bullet, sleep_off, false)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile3D_Wedge, sleep_off/continuous_off, false, 1, false)
    ->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile3D_Wedge, sleep_on, true)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile3D_Bullet, sleep_on, true)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile3D_Wedge, sleep_off/workers:2, false, 2)
    ->Iterations(kPileTimed)->UseRealTime()->Unit(benchmark::kMillisecond);

// ------------------------------------------------------------------ 3, 4. 4D piles

void Pile4D_Wedge(benchmark::State& state, int count, bool sleep, int workers = 1, bool continuous = true) {
  const bool big = count >= kBigPileCount;
  time_wedge<4>(state, settled_pile<4>(count, sleep, big ? kBigPileWarmup : kPileWarmup), kDt, workers, continuous);
}

BENCHMARK_CAPTURE(Pile4D_Wedge, 100/sleep_off, 100, false)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile4D_Wedge, 1000/sleep_off, 1000, false)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile4D_Wedge, 1000/sleep_off/continuous_off, 1000, false, 1, false)
    ->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile4D_Wedge, 1000/sleep_on, 1000, true)->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile4D_Wedge, 1000/sleep_off/workers:2, 1000, false, 2)
    ->Iterations(kPileTimed)->UseRealTime()->Unit(benchmark::kMillisecond);
// The goal's state: the same pile once settled, i.e. asleep. After 15 s a fifth of it is still awake
// (islands whose bodies have not all been still for time_to_sleep). Counter settled_s: the simulated
// time it took to fall asleep (the cap, 120 s, if it never did: then awake > 0 says so).
void Pile4D_Wedge_settled(benchmark::State& state) {
  const World<4>& start = settled_pile<4>(kPileCount, true, kSettledMaxWarmup, true);
  time_wedge<4>(state, start, kDt);
  state.counters["settled_s"] = start.time();
}
BENCHMARK(Pile4D_Wedge_settled)->Name("Pile4D_Wedge/1000/settled")->Iterations(kPileTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Pile4D_Wedge, 10000/sleep_off, kBigPileCount, false)
    ->Iterations(kBigPileTimed)
    ->Unit(benchmark::kMillisecond);

// ------------------------------------------------------------------ 5. the paper's scenes

// Steps per second (items_per_second) over the first kSceneTimed steps of the scene file, at its own
// time step and settings. A file that does not exist (yet) is reported as skipped.
void PaperScene(benchmark::State& state, const char* name) {
  const std::string path = std::string(WEDGE_SOURCE_DIR) + "/scenes/" + name + ".json";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("scene file not found: " + path).c_str());
    return;
  }
  try {
    const scenes::Scene<4> scene = scenes::load_scene_file<4>(path);
    const World<4>& start = settled<4>(path, 0, [&] { return scene.make_world(path); });
    time_wedge<4>(state, start, scene.timestep);
    state.SetItemsProcessed(state.iterations());
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

BENCHMARK_CAPTURE(PaperScene, fig1_stack_4d, "fig1_stack_4d")->Iterations(kSceneTimed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PaperScene, fig2_duocylinder_4d, "fig2_duocylinder_4d")
    ->Iterations(kSceneTimed)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PaperScene, fig3_dominoes_4d, "fig3_dominoes_4d")
    ->Iterations(kSceneTimed)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(PaperScene, fig4_spinning_4d, "fig4_spinning_4d")
    ->Iterations(kSceneTimed)
    ->Unit(benchmark::kMillisecond);

// What every loop a step splits over two threads pays beyond its work: the job handed to the helper
// (parallel::Workers bumps an epoch the helper spins on) and back (the helper counts itself done), each
// part writing one flag of its own. Two cache lines cross between the cores each way, so this follows
// the round trip of a cache line between them (bench/README.md, "the slow two-worker mode").
void Workers_HandOver(benchmark::State& state) {
  parallel::Workers workers(2);
  struct alignas(64) Flag {
    std::atomic<int> value{0};
  };
  Flag flags[2];
  for (auto _ : state)
    workers.for_parts(2, [&](int part, int) { flags[part].value.fetch_add(1, std::memory_order_relaxed); });
  if (flags[0].value.load() != flags[1].value.load()) state.SkipWithError("a part was not run");
}
BENCHMARK(Workers_HandOver)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
