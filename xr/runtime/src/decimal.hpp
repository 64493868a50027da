// Floats written to JSON as the shortest decimal that reads back as the same float (0.3f as 0.3, not as
// 0.30000001192092896, which is what widening it to double would print).
#pragma once

#include <charconv>
#include <cstdlib>

namespace wedge::xr_replay {

inline double float_as_decimal(float f) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf) - 1, f);
  if (ec != std::errc()) return double(f);
  *end = '\0';
  return std::strtod(buf, nullptr);
}

}  // namespace wedge::xr_replay
