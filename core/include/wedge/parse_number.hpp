// Numbers read from text a user wrote (command-line options, CSV fields): the whole text must be one
// finite decimal number in the C locale's form ("0.5", "-3e-2"). Anything else, "1e999" (overflow),
// "1e-999" (underflow), "inf", "nan", "" or "1.5x", is refused, for the caller to report with its place.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "wedge/fp_env.hpp"

namespace wedge {

// value is written only when the text is accepted.
inline bool parse_finite(const std::string& text, double& value) {
  if (text.empty()) return false;
  const ExpectedFpExceptions quiet;  // (strtod raises overflow for "1e999" by design)
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno == ERANGE || end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  value = v;
  return true;
}

}  // namespace wedge
