// One state line of `simulate` and `replay` (JSON Lines, docs/scene-format.md): time, energy, momenta and
// every body's state; and the check that a line about to be written is finite.
#pragma once

#include <string>

#include "json_out.hpp"
#include "scenes.hpp"
#include "step_options.hpp"

namespace wedge::cli {

template <int N>
OutJson state_line(const World<N>& world) {
  OutJson line;
  line["step"] = world.step_count();
  line["time"] = world.time();
  line["energy"] = world.kinetic_energy() + world.potential_energy();
  line["linear_momentum"] = to_json(world.linear_momentum());
  line["angular_momentum"] = to_json(world.angular_momentum());
  OutJson bodies = OutJson::array();
  for (int i = 0; i < world.body_count(); ++i) {
    const BodyId id{std::uint32_t(i)};
    const Body<N>& b = world.body(id);
    OutJson jb;
    jb["name"] = world.name(id);
    jb["position"] = to_json(Vec<N>(b.position()));
    jb["center"] = to_json(b.center);
    jb["rotor"] = to_json(b.rotor);
    jb["velocity"] = to_json(b.velocity);
    jb["angular_velocity"] = to_json(b.angular_velocity);
    jb["angular_momentum"] = to_json(b.angular_momentum());
    bodies.push_back(std::move(jb));
  }
  line["bodies"] = std::move(bodies);
  return line;
}

// The state is finite after checked_step; a non-finite line means a total or a body's momentum
// overflowed. Throws Failure naming the body or the total.
template <int N>
void check_finite_line(const OutJson& line, const World<N>& world, const std::string& file) {
  const std::string bad = first_non_finite(line);
  if (bad.empty()) return;
  std::string what = bad.substr(0, bad.find('[')), hint;
  if (what == "bodies") {
    const std::size_t i = std::stoul(bad.substr(7));
    const std::size_t dot = bad.find('.');
    what = bad.substr(dot + 1, bad.find('[', dot) - dot - 1) + " of body '" + world.name(BodyId{std::uint32_t(i)}) + "'";
  } else {
    what = "total " + what;
    hint = fastest_body(world) + "; ";
  }
  throw Failure(file + ": the " + what + " overflowed to a non-finite value at step " +
                std::to_string(world.step_count()) + " (" + hint + "are the initial speeds or masses too large?)");
}

}  // namespace wedge::cli
