// Counts the test binary's heap allocations while armed, so a test can assert that a step makes none.
// In a plain build this binary's malloc, calloc and realloc stand in for glibc's (interposed), so
// operator new and Eigen's aligned mallocs are counted alike; in a sanitizer build the sanitizer owns
// malloc, and its allocator's hook, which every allocation runs, counts instead (allocation_counter.cpp).
#pragma once

namespace allocation_counter {

// Allocations counted so far (only while armed).
long count();

// Armed for its lifetime (not nested).
class Armed {
 public:
  Armed();
  ~Armed();
  Armed(const Armed&) = delete;
  Armed& operator=(const Armed&) = delete;
};

}  // namespace allocation_counter
