// Environment variables -> Config (config.hpp).
#include "config.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>

namespace wedge::xr_replay {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? std::string() : std::string(v);
}

// A whole decimal number in [1, max]; false for anything else ("", "0", "12x", "-3").
bool parse_positive(std::string_view s, uint32_t max, uint32_t& out) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v == 0 || v > max) return false;
  out = uint32_t(v);
  return true;
}

}  // namespace

std::string read_config(Config& out) {
  out = Config{};
  out.replay_path = env("WEDGE_XR_REPLAY");
  out.haptics_log = env("WEDGE_XR_HAPTICS_LOG");
  out.frames_dir = env("WEDGE_XR_FRAMES");
  const std::string size = env("WEDGE_XR_EYE_SIZE");
  if (!size.empty()) {
    const std::size_t x = size.find('x');
    if (x == std::string::npos || !parse_positive(std::string_view(size).substr(0, x), 8192, out.eye_width) ||
        !parse_positive(std::string_view(size).substr(x + 1), 8192, out.eye_height))
      return "WEDGE_XR_EYE_SIZE=" + size + ": expected WIDTHxHEIGHT, each 1 to 8192 (e.g. 640x720)";
  }
  const std::string every = env("WEDGE_XR_FRAMES_EVERY");
  if (!every.empty() && !parse_positive(every, 1u << 30, out.frames_every))
    return "WEDGE_XR_FRAMES_EVERY=" + every + ": expected a whole number >= 1";
  const std::string refuse = env("WEDGE_XR_REFUSE");
  if (refuse == "system")
    out.refuse_system = true;
  else if (refuse == "session")
    out.refuse_session = true;
  else if (!refuse.empty())
    return "WEDGE_XR_REFUSE=" + refuse + ": expected system or session";
  const std::string quirks = env("WEDGE_XR_QUIRKS");
  for (std::size_t begin = 0; begin < quirks.size();) {
    const std::size_t end = std::min(quirks.find(',', begin), quirks.size());
    const std::string quirk = quirks.substr(begin, end - begin);
    begin = end + 1;
    if (quirk == "zero-display-time")
      out.zero_display_time = true;
    else if (quirk == "lose-tracking")
      out.lose_tracking = true;
    else if (quirk.rfind("refuse-binding=/", 0) == 0)
      out.refused_binding = quirk.substr(std::string("refuse-binding=").size());
    else
      return "WEDGE_XR_QUIRKS=" + quirks + ": unknown quirk '" + quirk +
             "' (expected zero-display-time, lose-tracking, refuse-binding=PATH, comma-separated)";
  }
  return "";
}

void report(const std::string& line) {
  std::fprintf(stderr, "Wedge replay runtime: %s\n", line.c_str());
  std::fflush(stderr);
}

}  // namespace wedge::xr_replay
