// The threads a World's step may use (WorldSettings::workers), internal. A loop over independent items
// (bodies, constraints of one colour) is cut into one contiguous range per thread; the calling thread
// takes the first range and waits for the others. Which thread runs an item never changes what is
// computed for it, and no item reads what another writes, so a step is bit-identical for any number of
// workers (tests/core/parallel/test_workers.cpp checks it).
//
// Helpers spin briefly between the many short loops of a step (Box2D v3 and Jolt do the same), then
// sleep on the futex behind std::atomic::wait, so an idle world costs no processor time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace wedge::parallel {

class Workers {
 public:
  static constexpr int kMax = 64;

  explicit Workers(int count = 1);
  // A copy has its own threads (as many): a copied World steps independently of the original.
  Workers(const Workers& o);
  Workers& operator=(const Workers& o);
  Workers(Workers&&) noexcept;
  Workers& operator=(Workers&&) noexcept;
  ~Workers();

  int count() const { return count_; }
  // Throws wedge::Error outside 1..kMax. Threads start on first use, so a world that never splits a
  // loop never starts one.
  void resize(int count);

  // Calls fn(begin, end) on contiguous ranges covering [0, n), one per thread, when every range gets at
  // least `grain` items; else fn(0, n) on the calling thread. Returns when all ranges are done; if fn
  // threw on any thread, rethrows the first exception then.
  template <class F>
  void for_ranges(int n, int grain, F&& fn) {
    const int parts = count_ > 1 && grain > 0 ? std::min(count_, n / grain) : 1;
    if (parts <= 1) {
      if (n > 0) fn(0, n);
      return;
    }
    for_parts(parts, [&](int part, int of) {
      fn(int(std::int64_t(n) * part / of), int(std::int64_t(n) * (part + 1) / of));
    });
  }

  // Calls fn(part, parts) for part = 0 .. parts - 1 (at most count()), each on its own thread, the
  // calling thread taking part 0; returns when all are done, rethrowing the first exception fn threw.
  template <class F>
  void for_parts(int parts, F&& fn) {
    if (parts <= 1) {
      fn(0, 1);
      return;
    }
    using Fn = std::remove_reference_t<F>;
    auto call = [](void* context, int part, int of) { (*static_cast<Fn*>(context))(part, of); };
    run(call, const_cast<void*>(static_cast<const void*>(&fn)), std::min(parts, count_));
  }

 private:
  struct Pool;
  using Call = void (*)(void* context, int part, int parts);
  void run(Call call, void* context, int parts);

  int count_ = 1;
  std::unique_ptr<Pool> pool_;  // started on first use with count_ - 1 helper threads
};

}  // namespace wedge::parallel
