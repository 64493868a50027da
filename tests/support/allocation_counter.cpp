#include "allocation_counter.hpp"

#include <atomic>
#include <cstddef>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define WEDGE_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define WEDGE_TEST_SANITIZED 1
#endif
#endif
#ifdef WEDGE_TEST_SANITIZED
#include <sanitizer/allocator_interface.h>
#endif

namespace {
std::atomic<bool> g_armed{false};
std::atomic<long> g_count{0};
}  // namespace

// Called on each counted allocation: `break wedge_counted_allocation` in a debugger finds the caller.
extern "C" __attribute__((noinline)) void wedge_counted_allocation() { g_count.fetch_add(1); }

namespace {
void on_allocation() {
  if (g_armed.load(std::memory_order_relaxed)) wedge_counted_allocation();
}
}  // namespace

#ifdef WEDGE_TEST_SANITIZED
namespace {
void malloc_hook(const volatile void*, std::size_t) { on_allocation(); }
void free_hook(const volatile void*) {}
const int g_hooks = __sanitizer_install_malloc_and_free_hooks(malloc_hook, free_hook);
}  // namespace
#else
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t n) noexcept {
  on_allocation();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  on_allocation();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) noexcept {
  on_allocation();
  return __libc_realloc(p, n);
}
}
#endif

namespace allocation_counter {

long count() { return g_count.load(); }
Armed::Armed() { g_armed = true; }
Armed::~Armed() { g_armed = false; }

}  // namespace allocation_counter
