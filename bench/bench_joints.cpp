// Joints (docs/joints.md), Wedge alone:
//   Chain4D/<links>   a chain of tesseracts (0.1 m cubes) on point joints at their faces, its first link
//                     pinned to the world, released straight out sideways: it falls, whips and folds,
//                     its links colliding with each other; default settings (60 Hz, 8 sub-steps)
// One benchmark iteration is one step at 60 Hz, after 1 s of untimed steps; one thread.
// Counters, so that a fast run that lets go shows up as such: gap_mm, the largest distance between a
// joint's two anchors after the timed steps (mm), and max_speed (m/s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <optional>
#include <vector>

#include "wedge_scenes.hpp"

namespace {

using namespace wedge;
using namespace wedge::bench;

constexpr int kWarmup = 60, kTimed = 120;

// (NaN if any gap is not finite: a run that blew up is not a time.)
template <int N>
double largest_gap_mm(const World<N>& w, const std::vector<JointId>& joints) {
  double gap = 0.0;
  for (const JointId j : joints) {
    const double g = (w.joint_anchor_b(j) - w.joint_anchor_a(j)).norm();
    if (!std::isfinite(g)) return std::nan("");
    gap = std::max(gap, g);
  }
  return 1e3 * gap;
}

template <int N>
void run(benchmark::State& state, World<N>& w, const std::vector<JointId>& joints) {
  for (int i = 0; i < kWarmup; ++i) w.step(kDt);
  for (auto _ : state) w.step(kDt);
  state.counters["gap_mm"] = largest_gap_mm(w, joints);
  state.counters["max_speed"] = max_speed(w);
}

void Chain4D(benchmark::State& state) {
  const int links = int(state.range(0));
  World<4> w(make_settings<4>(false));
  const double half = 0.05;  // m
  BodyDef<4> def = body_def<4>(std::make_shared<const Shape<4>>(Shape<4>::box(Vec<4>::Constant(half))), kDensity);
  std::vector<JointId> joints;
  std::optional<BodyId> previous;
  for (int i = 0; i < links; ++i) {
    def.position = Vec<4>((2 * i + 1) * half, 0.0, 0.0, 0.0);
    const BodyId link = w.add_body(def);
    PointJointDef<4> pin;  // at the face between this link and the one before (the world for the first)
    pin.body_a = previous;
    pin.anchor_a = previous ? Vec<4>(half, 0, 0, 0) : Vec<4>(Vec<4>::Zero());
    pin.body_b = link;
    pin.anchor_b = Vec<4>(-half, 0, 0, 0);
    joints.push_back(w.add_joint(pin));
    previous = link;
  }
  run(state, w, joints);
}

}  // namespace

BENCHMARK(Chain4D)->ArgName("links")->Arg(100)->Iterations(kTimed)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
