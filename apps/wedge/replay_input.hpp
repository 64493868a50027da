// Recordings driving a scene's World through the input layer: shared by `wedge replay` and
// `wedge render --replay`. Loads and merges the recordings (warnings to stderr), refuses the ones that
// cannot mean anything in the scene, and runs the input layer around each step.
#pragma once

#include <iostream>
#include <string>
#include <vector>

#include "scene_json.hpp"
#include "step_options.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/input/recording_source.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::cli {

template <int N>
input::InteractionSettings<N> interaction_settings(const Scene<N>& scene) {
  input::InteractionSettings<N> s;
  s.tracking.origin = scene.interaction.origin;
  s.tracking.scale = scene.interaction.scale;
  s.grab_radius = scene.interaction.grab_radius;
  s.gravity_tilt_on = scene.interaction.gravity_tilt_on;
  s.gravity_tilt_degrees = scene.interaction.gravity_tilt;
  return s;
}

inline input::RecordingSource load_recordings(const std::vector<std::string>& files) {
  std::vector<recordings::Recording> recs;
  try {
    for (const std::string& f : files) {
      recs.push_back(recordings::read_recording(f));
      for (const std::string& w : recs.back().warnings) std::cerr << "wedge: warning: " << w << "\n";
    }
    return input::RecordingSource(std::move(recs), files);
  } catch (const Error& e) {
    throw Failure(e.what());  // (the message starts with the file and line)
  }
}

// A recording that cannot mean anything in this scene is refused before anything runs.
template <int N>
void check_fit(const Scene<N>& scene, const input::RecordingSource& src, const std::vector<std::string>& files,
               const std::string& scene_file) {
  if (N < 4 && src.uses_mode4d()) {
    const int hand = src.source_of_hand(1) >= 0 ? 1 : 0;
    throw Failure(files[std::size_t(src.source_of_hand(hand))] + ": uses 4D rotation mode, but " + scene_file +
                  " is a " + std::to_string(N) + "D scene (no w to turn toward)");
  }
  if (N < 4 && src.uses_tilt())
    throw Failure(files[std::size_t(src.source_of_motion())] + ": turns on the gravity tilt toward w, but " +
                  scene_file + " is a " + std::to_string(N) + "D scene");
  if (src.has_motion() && scene.settings.gravity.squaredNorm() == 0.0)
    throw Failure(files[std::size_t(src.source_of_motion())] + ": has accelerometer samples to tilt gravity, but " +
                  scene_file + " has no gravity (set \"gravity\" in the scene)");
  if (!src.has_hands() && !src.has_motion())
    throw Failure(files.front() + ": holds no hand or accelerometer samples (nothing to replay)");
}

// The recordings and the input layer over one world.
template <int N>
class ReplayInput {
 public:
  ReplayInput(const Scene<N>& scene, World<N>& world, const std::vector<std::string>& files,
              const std::string& scene_file)
      : source_(load_recordings(files)), interaction_(make(scene, world, scene_file)) {
    check_fit(scene, source_, files, scene_file);
  }
  // Step k of h seconds with the input at t = k h around it (checked_step: Ctrl-C and non-finite states).
  void step(World<N>& world, std::int64_t k, double h, const std::string& scene_file) {
    interaction_.before_step(source_.frame_at(double(k) * h), h);
    checked_step(world, h, scene_file);
    interaction_.after_step();
  }
  const input::RecordingSource& source() const { return source_; }
  const input::Interaction<N>& interaction() const { return interaction_; }

 private:
  static input::Interaction<N> make(const Scene<N>& scene, World<N>& world, const std::string& file) {
    return with_file_context(file, "interaction", [&] { return input::Interaction<N>(world, interaction_settings(scene)); });
  }
  input::RecordingSource source_;
  input::Interaction<N> interaction_;
};

}  // namespace wedge::cli
