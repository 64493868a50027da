// The argument checks every entry point shares: structure types, next chains and the two-call idiom
// (capacity 0 asks for the count; a capacity below it is XR_ERROR_SIZE_INSUFFICIENT).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

// True when p points at a struct of type t (a wrong or missing struct is XR_ERROR_VALIDATION_FAILURE).
template <class T>
bool has_type(const T* p, XrStructureType t) {
  return p != nullptr && p->type == t;
}

// The first struct of type t in a next chain, or null.
inline const XrBaseInStructure* find_in_chain(const void* next, XrStructureType t) {
  for (auto* s = static_cast<const XrBaseInStructure*>(next); s != nullptr; s = s->next)
    if (s->type == t) return s;
  return nullptr;
}

// Two-call idiom over plain values.
template <class T>
XrResult two_call(uint32_t capacity, uint32_t* count, T* out, const std::vector<T>& items) {
  if (count == nullptr || (capacity > 0 && out == nullptr)) return XR_ERROR_VALIDATION_FAILURE;
  *count = uint32_t(items.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < items.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  for (std::size_t i = 0; i < items.size(); ++i) out[i] = items[i];
  return XR_SUCCESS;
}

// Two-call idiom over typed output structs: each of the first n must carry `type`; fill(i, out[i]) writes
// element i (keeping the app's type and next).
template <class T, class Fill>
XrResult two_call_structs(uint32_t capacity, uint32_t* count, T* out, uint32_t n, XrStructureType type, Fill fill) {
  if (count == nullptr || (capacity > 0 && out == nullptr)) return XR_ERROR_VALIDATION_FAILURE;
  *count = n;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
  for (uint32_t i = 0; i < n; ++i)
    if (out[i].type != type) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < n; ++i) fill(i, out[i]);
  return XR_SUCCESS;
}

// Two-call idiom over a string; the count includes the terminating NUL.
inline XrResult two_call_string(uint32_t capacity, uint32_t* count, char* buffer, const std::string& s) {
  if (count == nullptr || (capacity > 0 && buffer == nullptr)) return XR_ERROR_VALIDATION_FAILURE;
  *count = uint32_t(s.size() + 1);
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < s.size() + 1) return XR_ERROR_SIZE_INSUFFICIENT;
  std::memcpy(buffer, s.c_str(), s.size() + 1);
  return XR_SUCCESS;
}

// Copies s into a char buffer of `size` bytes (NUL-terminated, cut to fit).
inline void copy_string(char* dst, std::size_t size, const std::string& s) {
  const std::size_t n = s.size() < size - 1 ? s.size() : size - 1;
  std::memcpy(dst, s.data(), n);
  dst[n] = '\0';
}
template <std::size_t N>
void copy_string(char (&dst)[N], const std::string& s) {
  copy_string(dst, N, s);
}

// True when a fixed char array of N holds a NUL-terminated string that is not empty.
template <std::size_t N>
bool is_nonempty_cstring(const char (&s)[N]) {
  return s[0] != '\0' && std::memchr(s, '\0', N) != nullptr;
}

}  // namespace wedge::xr_replay
