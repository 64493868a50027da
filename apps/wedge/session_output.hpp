// What `wedge replay` and `wedge xr` write of an input session: state lines (simulate's plus gravity and
// the hands) every K steps, the grabs, releases and haptic pulses as event lines (event_json.hpp), and the
// counts for the closing summary. Both files appear whole at commit() or not at all (OutputSink).
#pragma once

#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>

#include "event_json.hpp"
#include "json_out.hpp"
#include "state_json.hpp"
#include "wedge/input/session.hpp"

namespace wedge::cli {

// The state hash as text (16 hex digits).
inline std::string hash_text(std::uint64_t hash) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, hash);
  return hex;
}

template <int N>
class SessionOutput {
 public:
  // `out` empty: states to stdout; `events` empty: no event file. `scene_file` names the scene in messages.
  SessionOutput(const std::string& scene_file, const std::string& out, const std::string& events, std::int64_t every)
      : scene_file_(scene_file), every_(every), out_(out) {
    if (!events.empty()) events_.emplace(events);
  }

  // The state line of the world as it is now.
  void write_state(const input::Session<N>& session) {
    const World<N>& world = session.world();
    const input::Interaction<N>& in = session.interaction();
    OutJson line = state_line(world);
    line["gravity"] = to_json(world.gravity());
    OutJson hands = OutJson::array();
    for (int k = 0; k < input::kHandCount; ++k) {
      OutJson jh;
      jh["hand"] = hand_name(k);
      jh["tracked"] = in.tracked(k);
      jh["point"] = to_json(in.hand_point(k));
      jh["holding"] = in.held(k) ? OutJson(world.name(*in.held(k))) : OutJson(nullptr);
      hands.push_back(std::move(jh));
    }
    line["hands"] = std::move(hands);
    check_finite_line(line, world, scene_file_);
    out_.write_line(line.dump());
  }

  // After each step: its grabs, releases and pulses to the event file (the session's output is cleared),
  // and the state line when the step count is a multiple of K.
  void after_step(input::Session<N>& session) {
    const World<N>& world = session.world();
    for (const input::InteractionEvent<N>& e : session.events()) {
      (e.kind == input::InteractionEvent<N>::Kind::Grab ? grabs_ : releases_)++;
      if (events_) events_->write_line(event_json(world, e).dump());
    }
    for (const input::HapticPulse<N>& p : session.pulses()) {
      ++pulses_;
      if (events_) events_->write_line(pulse_json(world, p).dump());
    }
    session.clear_output();
    if (session.step_count() % every_ == 0) write_state(session);
  }

  void write_hash(std::uint64_t hash) {
    OutJson line;
    line["state_hash"] = hash_text(hash);
    out_.write_line(line.dump());
  }

  void commit() {
    if (events_) events_->commit();
    out_.commit();
  }

  std::int64_t grabs() const { return grabs_; }
  std::int64_t releases() const { return releases_; }
  std::int64_t pulses() const { return pulses_; }

 private:
  std::string scene_file_;
  std::int64_t every_;
  OutputSink out_;
  std::optional<OutputSink> events_;
  std::int64_t grabs_ = 0, releases_ = 0, pulses_ = 0;
};

// "3 grabs", "1 release": a count and its noun, plural when it is not one.
inline std::string count_of(std::int64_t n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

}  // namespace wedge::cli
