// Where a step's time goes, Wedge and Box2D v3 side by side, from each engine's own stage profile
// (World::profile, b2World_GetProfile): the 2D pyramid of wedge_bench_peers, one thread, sleeping off,
// Box2D v3 at Wedge's stiffness (8 sub-steps, a 60 Hz contact spring) and at its defaults. Medians
// over the timed steps, in ms. Optional, built with wedge_bench_peers (bench/README.md, "Peers").
//   build-peers/bench/wedge_peers_profile [rows] [steps]
// Box2D's stages map onto Wedge's as the rows say; its `transforms` (each body's pose and box after
// the solve) are Wedge's broad-phase box update, done at the start of the next step.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "peer_box2d_v3.hpp"
#include "wedge_scenes.hpp"

namespace {

using namespace wedge;
using namespace wedge::bench;

constexpr int kStages = 9;
constexpr const char* kNames[kStages] = {"broad phase",         "narrow phase", "constraints",
                                         "solve (+ warm start)", "integrate positions", "relax",
                                         "finish (+ restitution)", "islands, events", "step"};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Each stage's median over `steps` steps after a 2-s settle, in ms.
template <typename Step, typename Stages>
std::vector<double> profile(int steps, Step step, Stages stages) {
  for (int i = 0; i < 120; ++i) step();
  std::vector<std::vector<double>> at(kStages);
  for (int i = 0; i < steps; ++i) {
    step();
    const auto s = stages();
    for (int k = 0; k < kStages; ++k) at[k].push_back(s[k]);
  }
  std::vector<double> out;
  for (const auto& v : at) out.push_back(median(v));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int rows = argc > 1 ? std::atoi(argv[1]) : 100, steps = argc > 2 ? std::atoi(argv[2]) : 300;
  if (rows < 2 || steps < 1) {
    std::fprintf(stderr, "usage: wedge_peers_profile [rows >= 2] [steps >= 1]\n");
    return 2;
  }
  World<2> wedge_world = wedge_pyramid(rows, false);
  const World<2> layout = wedge_world;
  const auto wedge = profile(
      steps, [&] { wedge_world.step(kDt); },
      [&] {
        const StepProfile& p = wedge_world.profile();
        return std::vector<double>{1e3 * p.broad_phase,         1e3 * p.narrow_phase, 1e3 * p.constraints,
                                   1e3 * p.solve,               1e3 * p.integrate_positions,
                                   1e3 * p.relax,               1e3 * p.finish,
                                   1e3 * (p.islands + p.events), 1e3 * p.step};
      });
  auto box2d = [&](int substeps, float hertz) {
    Box2DV3Scene scene(layout, false, 1, substeps, hertz);
    return profile(
        steps, [&] { scene.step(); },
        [&] {
          const b2Profile p = b2World_GetProfile(scene.world());
          return std::vector<double>{p.pairs + p.refit,
                                     p.collide,
                                     p.prepareConstraints + p.solverSetup,
                                     p.integrateVelocities + p.warmStart + p.solveImpulses,
                                     p.integratePositions,
                                     p.relaxImpulses,
                                     p.applyRestitution + p.storeImpulses + p.transforms,
                                     p.splitIslands + p.sleepIslands + p.hitEvents,
                                     p.step};
        });
  };
  const auto stiff = box2d(8, 60.0f), defaults = box2d(4, 0.0f);
  std::printf("2D pyramid, %d rows, one thread, median of %d steps (ms)\n", rows, steps);
  std::printf("%-24s %10s %14s %10s %14s\n", "stage", "Wedge", "Box2D v3 8/60", "ratio", "Box2D v3 dflt");
  for (int k = 0; k < kStages; ++k)
    std::printf("%-24s %10.3f %14.3f %9.2fx %14.3f\n", kNames[k], wedge[k], stiff[k],
                stiff[k] > 0.0 ? wedge[k] / stiff[k] : 0.0, defaults[k]);
  std::printf("(the stages' medians need not add up to the step's)\n");
  return 0;
}
