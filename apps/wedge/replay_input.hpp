// Recordings driving a scene's World through an input session: shared by `wedge replay`, `wedge render
// --replay` and `wedge view --replay`. Loads and merges the recordings (warnings to stderr), refuses the ones that
// cannot mean anything in the scene, and runs the input layer around each step.
#pragma once

#include <iostream>
#include <string>
#include <vector>

#include "scenes.hpp"
#include "wedge/scenes/interaction.hpp"
#include "step_options.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/input/session.hpp"
#include "wedge/recordings/recording_source.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::cli {

inline recordings::RecordingSource load_recordings(const std::vector<std::string>& files) {
  std::vector<recordings::Recording> recs;
  try {
    for (const std::string& f : files) {
      recs.push_back(recordings::read_recording(f));
      for (const std::string& w : recs.back().warnings) std::cerr << "wedge: warning: " << w << "\n";
    }
    return recordings::RecordingSource(std::move(recs), files);
  } catch (const Error& e) {
    throw Failure(e.what());  // (the message starts with the file and line)
  }
}

// A recording that cannot mean anything in this scene is refused before anything runs.
template <int N>
void check_fit(const Scene<N>& scene, const recordings::RecordingSource& src, const std::vector<std::string>& files,
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

// An input session over one world whose steps are checked as every verb's are (checked_step: Ctrl-C,
// non-finite states named with the scene file).
template <int N>
input::Session<N> make_session(const Scene<N>& scene, World<N>& world, double h, const std::string& scene_file) {
  input::Session<N> session =
      with_file_context(scene_file, "interaction", [&] { return input::Session<N>(world, scenes::session_settings(scene, h)); });
  session.set_step_function([scene_file](World<N>& w, double step) { checked_step(w, step, scene_file); });
  return session;
}

// Recordings driving one world through an input session: step k takes the recordings' frame at t = k h.
template <int N>
class ReplayInput {
 public:
  ReplayInput(const Scene<N>& scene, World<N>& world, const std::vector<std::string>& files,
              const std::string& scene_file, double h)
      : source_(load_recordings(files)), session_(make_session(scene, world, h, scene_file)) {
    check_fit(scene, source_, files, scene_file);
  }
  // The next step, with the recordings' input at its start time.
  void step() { session_.step(source_.frame_at(session_.time())); }
  const recordings::RecordingSource& source() const { return source_; }
  input::Session<N>& session() { return session_; }
  const input::Session<N>& session() const { return session_; }
  const input::Interaction<N>& interaction() const { return session_.interaction(); }

 private:
  recordings::RecordingSource source_;
  input::Session<N> session_;
};

}  // namespace wedge::cli
