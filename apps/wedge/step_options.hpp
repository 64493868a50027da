// Options shared by the verbs that step a scene (simulate, render): strict parsing of the numeric
// option texts (so that every message names the scene file) and the check for a blown-up state.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

#include "cli_error.hpp"
#include "interrupt.hpp"
#include "scenes.hpp"
#include "wedge/parse_number.hpp"
#include "wedge/world.hpp"

namespace wedge::cli {

// The whole text must be a number.
inline bool parse_int64(const std::string& text, std::int64_t& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

// A picture or window size, --size WIDTHxHEIGHT (px).
struct Size {
  int width = 1280, height = 720;
};

// --size WxH with min_width..8192 by min_height..8192 (default 1280x720); throws Failure naming `scene`.
inline Size parse_size(const std::string& scene, const std::string& text, int min_width, int min_height) {
  Size s;
  if (text.empty()) return s;
  const std::size_t x = text.find('x');
  std::int64_t w = 0, h = 0;
  if (x == std::string::npos || !parse_int64(text.substr(0, x), w) || !parse_int64(text.substr(x + 1), h) ||
      w < min_width || h < min_height || w > 8192 || h > 8192)
    throw Failure(scene + ": --size must be WIDTHxHEIGHT, at least " + std::to_string(min_width) + "x" +
                  std::to_string(min_height) + " and at most 8192x8192 pixels (got '" + text + "')");
  s.width = int(w);
  s.height = int(h);
  return s;
}

struct StepOptions {
  std::int64_t steps = 0, every = 1;
  std::optional<double> dt;
};

// --steps N (required, >= 0), --every K (>= 1), --dt H (in [kMinTimestep, kMaxTimestep] s); throws Failure
// naming `scene`.
inline StepOptions parse_step_options(const std::string& scene, const std::string& steps, const std::string& dt,
                                      const std::string& every) {
  const std::string prefix = scene + ": ";
  StepOptions run;
  if (steps.empty()) throw Failure(prefix + "--steps N is required");
  if (!parse_int64(steps, run.steps) || run.steps < 0)
    throw Failure(prefix + "--steps must be an integer >= 0 (got '" + steps + "')");
  if (!every.empty() && (!parse_int64(every, run.every) || run.every < 1))
    throw Failure(prefix + "--every must be an integer >= 1 (got '" + every + "')");
  if (!dt.empty()) {
    double h = 0.0;
    if (!parse_finite(dt, h) || !(h >= kMinTimestep && h <= kMaxTimestep))
      throw Failure(prefix + "--dt must be a step size in [1e-6, 0.1] s (got '" + dt + "')");
    run.dt = h;
  }
  return run;
}

// --workers N (WorldSettings::workers, 1..64; default 1); throws Failure naming `scene`.
inline int parse_workers(const std::string& scene, const std::string& text) {
  std::int64_t n = 1;
  if (!text.empty() && (!parse_int64(text, n) || n < 1 || n > 64))
    throw Failure(scene + ": --workers must be an integer in 1..64 (got '" + text + "')");
  return int(n);
}

// The first body whose state is not finite and the quantity that is not: {-1, ""} if all are.
template <int N>
std::pair<int, const char*> first_non_finite_state(const World<N>& world) {
  for (int i = 0; i < world.body_count(); ++i) {
    const Body<N>& b = world.body(BodyId{std::uint32_t(i)});
    if (!all_finite(b.center)) return {i, "position"};
    if (!b.rotor.all_finite()) return {i, "rotor"};
    if (!all_finite(b.velocity)) return {i, "velocity"};
    if (!b.angular_velocity.all_finite()) return {i, "angular velocity"};
  }
  return {-1, ""};
}

// The body with the largest speed (m/s): the likely cause when a total overflows.
template <int N>
std::string fastest_body(const World<N>& world) {
  int best = -1;
  double speed = -1.0;
  for (int i = 0; i < world.body_count(); ++i) {
    const double v = world.body(BodyId{std::uint32_t(i)}).velocity.stableNorm();  // no overflow of the squares
    if (!(v <= speed)) best = i, speed = v;
  }
  if (best < 0) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%.3g m/s", speed);
  return "the fastest body is '" + world.name(BodyId{std::uint32_t(best)}) + "' at " + text;
}

// Steps once and throws Failure naming the body and the quantity if a state became non-finite.
template <int N>
void step_checking_finite(World<N>& world, double h, const std::string& scene) {
  world.step(h);
  const auto [bad, what] = first_non_finite_state(world);
  if (bad >= 0)
    throw Failure(scene + ": the simulation produced a non-finite " + what + " of body '" +
                  world.name(BodyId{std::uint32_t(bad)}) + "' at step " + std::to_string(world.step_count()) +
                  " (are the step size or the initial speeds too large?)");
}

// The same after a check for Ctrl-C (which unwinds, removing partial output).
template <int N>
void checked_step(World<N>& world, double h, const std::string& scene) {
  throw_if_interrupted();
  step_checking_finite(world, h, scene);
}

}  // namespace wedge::cli
