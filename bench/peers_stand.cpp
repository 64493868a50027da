// Issue 15's bar for tall stacks, applied to Wedge and Box2D v3 alike: the 100-row 2D pyramid (Box2D's
// "large pyramid", 5,050 boxes, the layout of wedge_bench_peers) stands for 60 s with sleeping off, no
// box faster than 0.5 m/s after the first 2 s, the top box sinking less than 0.25 m. Prints each
// engine's result at its defaults and Box2D v3 at Wedge's stiffness (8 sub-steps, a 60 Hz contact
// spring; both engines cap the spring at an eighth of the sub-step rate). Optional, built with
// wedge_bench_peers (bench/README.md, "Peers"); about a minute.
//   build-peers/bench/wedge_peers_stand [rows] [seconds]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "peer_box2d_v3.hpp"
#include "wedge_scenes.hpp"

namespace {

using namespace wedge;
using namespace wedge::bench;

// Steps the scene for `seconds` at 60 Hz; prints the top's sink and the fastest box after 2 s.
template <typename Step, typename Top, typename Fastest>
void stand(const std::string& name, int seconds, Step step, Top top, Fastest fastest) {
  const double y0 = top();
  double fast = 0.0;
  for (int i = 0; i < seconds * 60; ++i) {
    step();
    if (i >= 2 * 60) fast = std::max(fast, fastest());
  }
  const double sink = y0 - top();
  std::printf("%-44s top sank %.3f m, fastest after 2 s %.3f m/s: %s\n", name.c_str(), sink, fast,
              sink < 0.25 && fast < 0.5 ? "meets the bar" : "misses the bar");
}

}  // namespace

int main(int argc, char** argv) {
  const int rows = argc > 1 ? std::atoi(argv[1]) : 100, seconds = argc > 2 ? std::atoi(argv[2]) : 60;
  if (rows < 2 || seconds < 3) {
    std::fprintf(stderr, "usage: wedge_peers_stand [rows >= 2] [seconds >= 3]\n");
    return 2;
  }
  std::printf("%d-row 2D pyramid, %d s at 60 Hz, sleeping off (bar: sink < 0.25 m, < 0.5 m/s after 2 s)\n", rows,
              seconds);
  {
    World<2> w = peers_pyramid(rows);
    stand("Wedge, defaults (8 sub-steps, 60 Hz)", seconds, [&] { w.step(kDt); },
          [&] { return w.bodies().back().center[1]; }, [&] { return max_speed(w); });
  }
  const World<2> layout = peers_pyramid(rows);
  const auto box2d = [&](const char* name, int substeps, float hertz) {
    Box2DV3Scene b(layout, false, 1, substeps, hertz);
    stand(name, seconds, [&] { b.step(); }, [&] { return b.height(b.count() - 1); }, [&] { return b.max_speed(); });
  };
  box2d("Box2D v3, defaults (4 sub-steps, 30 Hz)", 4, 0.0f);
  box2d("Box2D v3, 8 sub-steps, 30 Hz", 8, 0.0f);
  box2d("Box2D v3 at Wedge's (8 sub-steps, 60 Hz)", 8, 60.0f);
}
