// WorldSettings::workers (core/src/parallel/workers.cpp): loops are cut into contiguous ranges that
// cover every item once, the helpers really run them, and a step's state is bit-identical for any
// number of workers, in every solver and dimension, for piles large enough that the solver's colours
// are split.
#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "wedge/scenes/builders.hpp"
#include "parallel/workers.hpp"
#include "wedge/error.hpp"
#include "wedge/mass.hpp"
#include "wedge/world.hpp"

using namespace wedge;
using parallel::Workers;

namespace {

// The process's thread count (Linux): helpers are started on the first split loop.
// ThreadSanitizer's runtime starts a background thread of its own when the process first starts one.
#if defined(__SANITIZE_THREAD__)
constexpr bool kThreadSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr bool kThreadSanitizer = true;
#else
constexpr bool kThreadSanitizer = false;
#endif
#else
constexpr bool kThreadSanitizer = false;
#endif

int thread_count() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
  return -1;
}

struct Range {
  int begin, end;
  std::thread::id thread;
};

std::vector<Range> ranges_of(Workers& workers, int n, int grain) {
  std::mutex m;
  std::vector<Range> ranges;
  workers.for_ranges(n, grain, [&](int begin, int end) {
    const std::lock_guard<std::mutex> lock(m);
    ranges.push_back({begin, end, std::this_thread::get_id()});
  });
  std::sort(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) { return a.begin < b.begin; });
  return ranges;
}

// The ranges are contiguous, in order, and cover [0, n) exactly once.
void check_cover(const std::vector<Range>& ranges, int n) {
  int next = 0;
  for (const Range& r : ranges) {
    CHECK(r.begin == next);
    CHECK(r.end > r.begin);
    next = r.end;
  }
  CHECK(next == n);
}

// Steps copies of `start` with 1, 2 and 3 workers and requires bit-identical state hashes after every
// step; returns the hash after the last.
template <int N>
std::uint64_t same_for_any_workers(const World<N>& start, int steps, double h) {
  std::vector<World<N>> worlds;
  for (const int workers : {1, 2, 3}) {
    worlds.push_back(start);
    worlds.back().update_settings([&](auto& s) { s.workers = workers; });
  }
  const int before = thread_count();
  int mismatches = 0;
  for (int i = 0; i < steps; ++i) {
    for (World<N>& w : worlds) w.step(h);
    mismatches += worlds[1].state_hash() != worlds[0].state_hash() || worlds[2].state_hash() != worlds[0].state_hash();
  }
  // The helpers of the 2- and 3-worker worlds ran (1 + 2 threads): the split paths were taken. (Under
  // ThreadSanitizer its runtime's own thread may join them.)
  const int started = thread_count() - before;
  CHECK((started == 3 || (kThreadSanitizer && started == 4)));
  CHECK(mismatches == 0);
  return worlds[0].state_hash();
}

template <int N>
World<N> pile(int count, ContactSolver solver) {
  WorldSettings<N> s;
  s.gravity = -9.81 * Vec<N>::Unit(1);
  s.contact.solver = solver;
  s.contact.allow_sleep = false;
  World<N> w(s);
  scenes::add_ground<N>(w);
  scenes::add_box_pile<N>(w, count);
  return w;
}

}  // namespace

TEST_CASE("workers: for_ranges covers every item once, on the helpers only when each gets a grain",
          "[workers]") {
  Workers one(1), two(2), four(4);
  for (const int n : {0, 1, 7, 64, 1000, 1001}) {
    INFO("n = " << n);
    check_cover(ranges_of(one, n, 1), n);
    check_cover(ranges_of(two, n, 1), n);
    check_cover(ranges_of(four, n, 1), n);
  }
  // 1,000 items of grain 10 over 2 threads: two halves, the first on the calling thread.
  std::vector<Range> r = ranges_of(two, 1000, 10);
  REQUIRE(r.size() == 2);
  CHECK(r[0].end == 500);
  CHECK(r[0].thread == std::this_thread::get_id());
  CHECK(r[1].thread != std::this_thread::get_id());
  // Fewer than two grains: all of it here. Three grains over four threads: three ranges.
  r = ranges_of(two, 19, 10);
  REQUIRE(r.size() == 1);
  CHECK(r[0].thread == std::this_thread::get_id());
  r = ranges_of(four, 30, 10);
  CHECK(r.size() == 3);
  std::set<std::thread::id> threads;
  for (const Range& x : ranges_of(four, 4000, 10)) threads.insert(x.thread);
  CHECK(threads.size() == 4);
}

TEST_CASE("workers: a helper that fell asleep wakes for the next loop, and a copy has threads of its own",
          "[workers]") {
  Workers two(2);
  check_cover(ranges_of(two, 100, 10), 100);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // past the spin: the helper sleeps
  const std::vector<Range> r = ranges_of(two, 100, 10);
  check_cover(r, 100);
  REQUIRE(r.size() == 2);
  CHECK(r[1].thread != std::this_thread::get_id());
  Workers copy = two;
  const std::vector<Range> c = ranges_of(copy, 100, 10);
  REQUIRE(c.size() == 2);
  CHECK(c[1].thread != r[1].thread);
}

TEST_CASE("workers: an exception on any thread reaches the caller once all ranges are done", "[workers]") {
  Workers two(2);
  for (const int bad : {10, 90}) {  // in the calling thread's range, then in the helper's
    INFO("item " << bad << " throws");
    std::atomic<int> done{0};
    CHECK_THROWS_WITH(two.for_ranges(100, 10,
                                     [&](int begin, int end) {
                                       for (int i = begin; i < end; ++i) {
                                         if (i == bad) throw Error("item " + std::to_string(i));
                                         ++done;
                                       }
                                     }),
                      "item " + std::to_string(bad));
    CHECK(done == 50 + bad % 50);  // the other range ran to its end, this one up to the throw
    check_cover(ranges_of(two, 100, 10), 100);            // and the workers still work
  }
}

TEST_CASE("workers: out of 1..64 is refused with a message naming the setting", "[workers]") {
  Workers w;
  CHECK_THROWS_WITH(w.resize(0), Catch::Contains("workers must be in 1..64"));
  CHECK_THROWS_WITH(w.resize(65), Catch::Contains("workers must be in 1..64"));
  WorldSettings<3> s;
  s.workers = 0;
  CHECK_THROWS_WITH(World<3>(s), Catch::Contains("workers"));
  World<3> world;
  CHECK_THROWS_WITH(world.update_settings([&](auto& ws) { ws.workers = -2; }), Catch::Contains("workers must be in 1..64"));
  CHECK(world.settings().workers == 1);  // refused: unchanged
}

TEST_CASE("workers: piles step bit-identically with 1, 2 and 3 workers (soft step, 2D-4D)", "[workers][contact]") {
  // Sizes where the first colours hold hundreds of constraints (so they are split), stepped through
  // the fall, the impacts and the heap's first seconds.
  same_for_any_workers(pile<2>(400, ContactSolver::SoftStep), 120, 1.0 / 60.0);
  same_for_any_workers(pile<3>(300, ContactSolver::SoftStep), 120, 1.0 / 60.0);
  same_for_any_workers(pile<4>(200, ContactSolver::SoftStep), 120, 1.0 / 60.0);
}

// Restitution runs after the sub-steps, colour by colour, each colour split over the workers. Boxes
// dropped in layers 1.5 m apart onto the ground and onto each other hit at 4-7 m/s, above
// restitution_threshold (1 m/s), so restitution acts on hundreds of points at once. That it did: with
// restitution 0.5 some box rises at over 1 m/s (about 2 m/s, of e u = 2-3.5 m/s less what the boxes
// above take), and with restitution 0 none does (the contacts' push alone: 0.7-0.9 m/s).
TEST_CASE("workers: restitution is bit-identical with 1, 2 and 3 workers (soft step, 2D, 3D)", "[workers][contact]") {
  const auto check = [](auto dimension) {
    constexpr int N = decltype(dimension)::value;
    const auto make = [](double restitution) {
      WorldSettings<N> s;
      s.gravity = -9.81 * Vec<N>::Unit(1);
      s.contact.allow_sleep = false;
      World<N> w(s);
      scenes::add_ground<N>(w);
      const auto box = std::make_shared<const Shape<N>>(Shape<N>::box(Vec<N>::Constant(0.5)));
      const int side = N == 2 ? 30 : 8;
      for (int i = 0; i < (N == 2 ? 300 : 256); ++i) {
        BodyDef<N> d = body_def<N>(box, 1000.0);
        d.material.restitution = restitution;
        d.position[0] = 1.1 * (i % side);
        if constexpr (N == 3) d.position[2] = 1.1 * (i / side % side);
        d.position[1] = 1.5 + 1.5 * (N == 2 ? i / side : i / (side * side));
        w.add_body(d);
      }
      return w;
    };
    const auto fastest_rise = [](World<N> w) {  // m/s, the fastest upward speed of any box in 2 s
      double rising = 0.0;
      for (int i = 0; i < 120; ++i) {
        w.step(1.0 / 60.0);
        for (const Body<N>& b : w.bodies()) rising = std::max(rising, b.velocity[1]);
      }
      return rising;
    };
    const World<N> bouncy = make(0.5);
    const double with = fastest_rise(bouncy), without = fastest_rise(make(0.0));
    INFO(N << "D: fastest rise " << with << " m/s with restitution 0.5, " << without << " m/s without");
    CHECK(with > 1.0);
    CHECK(without < 1.0);
    same_for_any_workers(bouncy, 120, 1.0 / 60.0);
  };
  check(std::integral_constant<int, 2>{});
  check(std::integral_constant<int, 3>{});
}

TEST_CASE("workers: the paper's solver steps bit-identically with 1, 2 and 3 workers", "[workers][contact]") {
  same_for_any_workers(pile<3>(400, ContactSolver::Paper), 150, 1.0 / 60.0);
}
