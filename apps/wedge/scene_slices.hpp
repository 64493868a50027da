// The slice options of `wedge render` and `wedge slice` (--w, --subdivisions) and the scene's World
// prepared for slicing by the library piece slicing::WorldSlices.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "scenes.hpp"
#include "step_options.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/slicing/world_slices.hpp"

namespace wedge::cli {

// Default tessellation levels for display (finer than the core's mass-property default): 24576
// tetrahedra per 4-ball, 61440 4-simplices per 5-ball.
constexpr int default_display_subdivisions(int n) { return n <= 3 ? 16 : (n == 4 ? 8 : (n == 5 ? 4 : 2)); }

// "W" or "W1,W2,..": up to n-3 slice offsets (m); missing ones are 0. Throws Failure naming the scene.
inline std::vector<double> parse_slice_offsets(const std::string& scene, const std::string& text, int n) {
  std::vector<double> w;
  if (text.empty()) return w;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double v = 0.0;
    if (!parse_finite(part, v) || !std::isfinite(v))
      throw Failure(scene + ": --w must be a number, or comma-separated numbers for 5D and 6D (got '" + text + "')");
    w.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (int(w.size()) > std::max(n - 3, 0))
    throw Failure(scene + ": --w takes " + (n <= 3 ? std::string("no offsets in a ") + std::to_string(n) + "D scene (it is shown as it is)"
                                                   : "at most " + std::to_string(n - 3) + " offset(s) in a " + std::to_string(n) + "D scene") +
                  " (got '" + text + "')");
  return w;
}

// The viewer's level while a scene plays: about 5/8 of the still level (8 -> 5 in 4D, 4 -> 3 in 5D), which
// keeps the 4D figure scenes' physics plus slicing under 2 ms a frame (bench/README.md).
constexpr int default_play_subdivisions(int subdivisions) { return std::max(1, (5 * subdivisions + 7) / 8); }

inline int parse_subdivisions(const std::string& scene, const std::string& text, int n,
                              const char* option = "--subdivisions") {
  if (text.empty()) return default_display_subdivisions(n);
  std::int64_t s = 0;
  if (!parse_int64(text, s) || s < 1 || s > 64) {
    std::string message = scene + ": ";
    message += option;
    message += " must be an integer in 1..64 (got '";
    message += text;
    message += "')";
    throw Failure(message);
  }
  return int(s);
}

// The scene's World prepared for slicing (slicing::WorldSlices, shared with the viewer and the OpenXR
// app); a shape that cannot be tessellated is named with the file.
template <int N>
slicing::WorldSlices<N> scene_slices(const World<N>& world, const std::vector<double>& w, int subdivisions,
                                     const std::string& file, int coarse_subdivisions = 0) {
  return with_file_context(file, "",
                           [&] { return slicing::WorldSlices<N>(world, w, subdivisions, coarse_subdivisions); });
}

}  // namespace wedge::cli
