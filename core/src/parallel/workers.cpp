#include "parallel/workers.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "wedge/error.hpp"

namespace wedge::parallel {

namespace {
void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}
// How long a helper spins for the next loop before it sleeps: longer than the serial work between two
// loops of a step (small colours, the narrow phase of a few pairs), far shorter than a frame.
constexpr auto kSpin = std::chrono::microseconds(200);
}  // namespace

// Every helper acknowledges every job (pending counts them all), so none can lag into the next one.
struct Workers::Pool {
  std::vector<std::thread> threads;
  std::atomic<std::uint32_t> epoch{0};  // bumped once per job (and to stop)
  std::atomic<int> pending{0};          // helpers that have not finished the current job
  std::atomic<int> sleepers{0};         // helpers blocked in epoch.wait
  bool stop = false;
  // The job, written before epoch is bumped.
  Call call = nullptr;
  void* context = nullptr;
  int parts = 0;
  std::mutex error_mutex;
  std::exception_ptr error;  // the first exception of the current job, rethrown by run() once all are done

  void keep(std::exception_ptr e) {
    const std::lock_guard<std::mutex> lock(error_mutex);
    if (!error) error = std::move(e);
  }

  explicit Pool(int helpers) {
    for (int i = 1; i <= helpers; ++i) threads.emplace_back([this, i] { serve(i); });
  }
  ~Pool() {
    stop = true;
    epoch.fetch_add(1);
    epoch.notify_all();
    for (std::thread& t : threads) t.join();
  }

  void serve(int part) {
    std::uint32_t seen = 0;
    for (;;) {
      seen = next_epoch(seen);
      if (stop) return;
      if (part < parts) {
        try {
          call(context, part, parts);
        } catch (...) {
          keep(std::current_exception());
        }
      }
      pending.fetch_sub(1, std::memory_order_release);
    }
  }

  std::uint32_t next_epoch(std::uint32_t seen) {
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (int i = 1;; ++i) {
      const std::uint32_t e = epoch.load(std::memory_order_acquire);
      if (e != seen) return e;
      pause();
      if (i % 64 == 0 && std::chrono::steady_clock::now() > until) break;
    }
    // seq_cst with run()'s bump and check of sleepers: either run() sees this sleeper and notifies, or
    // this thread sees the new epoch below (no lost wake-up).
    sleepers.fetch_add(1);
    std::uint32_t e;
    while ((e = epoch.load()) == seen) epoch.wait(seen);
    sleepers.fetch_sub(1);
    return e;
  }
};

Workers::Workers(int count) { resize(count); }
Workers::Workers(const Workers& o) : Workers(o.count_) {}
Workers& Workers::operator=(const Workers& o) {
  if (this != &o) resize(o.count_);
  return *this;
}
Workers::Workers(Workers&&) noexcept = default;
Workers& Workers::operator=(Workers&&) noexcept = default;
Workers::~Workers() = default;

void Workers::resize(int count) {
  if (count < 1 || count > kMax)
    throw Error("workers must be in 1.." + std::to_string(kMax) + " (got " + std::to_string(count) + ")");
  if (count == count_) return;
  pool_.reset();
  count_ = count;
}

void Workers::run(Call call, void* context, int parts) {
  if (!pool_) pool_ = std::make_unique<Pool>(count_ - 1);
  Pool& p = *pool_;
  p.call = call;
  p.context = context;
  p.parts = parts;
  p.error = nullptr;
  p.pending.store(int(p.threads.size()), std::memory_order_relaxed);
  p.epoch.fetch_add(1);
  if (p.sleepers.load() > 0) p.epoch.notify_all();
  try {
    call(context, 0, parts);
  } catch (...) {
    p.keep(std::current_exception());
  }
  // Always wait for the helpers, even after an exception here: they use the caller's stack.
  for (int i = 1; p.pending.load(std::memory_order_acquire) != 0; ++i) {
    pause();
    if (i % 1024 == 0) std::this_thread::yield();  // (a helper still waking from its sleep)
  }
  if (p.error) std::rethrow_exception(p.error);
}

}  // namespace wedge::parallel
