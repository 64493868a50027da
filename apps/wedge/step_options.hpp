// Options shared by the verbs that step a scene (simulate, render): strict parsing of the numeric
// option texts (so that every message names the scene file) and the check for a blown-up state.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "cli_error.hpp"
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
inline bool parse_double(const std::string& text, double& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno == ERANGE || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

struct StepOptions {
  std::int64_t steps = 0, every = 1;
  std::optional<double> dt;
};

// --steps N (required, >= 0), --every K (>= 1), --dt H (finite, > 0); throws Failure naming `scene`.
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
    if (!parse_double(dt, h) || !std::isfinite(h) || !(h > 0.0))
      throw Failure(prefix + "--dt must be a finite number > 0 (got '" + dt + "')");
    run.dt = h;
  }
  return run;
}

// The first body whose state is not finite, or -1.
template <int N>
int first_non_finite_body(const World<N>& world) {
  for (int i = 0; i < world.body_count(); ++i) {
    const Body<N>& b = world.body(BodyId{std::uint32_t(i)});
    if (!b.center.allFinite() || !b.rotor.all_finite() || !b.velocity.allFinite() ||
        !b.angular_velocity.all_finite())
      return i;
  }
  return -1;
}

// Steps once and throws Failure if a body's state became non-finite.
template <int N>
void checked_step(World<N>& world, double h, const std::string& scene) {
  world.step(h);
  const int bad = first_non_finite_body(world);
  if (bad >= 0)
    throw Failure(scene + ": the simulation produced a non-finite value at step " + std::to_string(world.step_count()) +
                  " (body '" + world.name(BodyId{std::uint32_t(bad)}) + "'; step size too large?)");
}

}  // namespace wedge::cli
