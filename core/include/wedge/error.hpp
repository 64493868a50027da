// The one exception type of the library: invalid input (degenerate geometry, bad sizes, non-positive
// mass). Thrown only while building things (shapes, bodies, scenes), never from inside World::step.
// Front ends catch it, prefix the file name, print it and exit with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace wedge {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace wedge
