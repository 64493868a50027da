// The one exception type of the library: invalid input (degenerate geometry, bad sizes, non-positive
// mass). Thrown only while building things (shapes, bodies, scenes), never from inside World::step.
// Front ends catch it, prefix the file name, print it and exit with code 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace wedge {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// A user's text (a key, a name, a field) as an error message may quote it: on one line, control characters
// and other bytes outside printable ASCII written as \n, \r, \t or \xNN, and cut after 40 characters with
// "...". A key "a\nb" in a file is named 'a\nb' instead of breaking the message in two.
inline std::string printable(std::string_view text) {
  constexpr std::size_t kShown = 40;
  constexpr const char* kHex = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c >= 0x7f) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += char(c);
    }
  }
  if (text.size() > kShown) out += "...";
  return out;
}

}  // namespace wedge
