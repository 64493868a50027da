// Replays a recorded session (hands and accelerometer, docs/recording-format.md) into a 4D scene file,
// headless, and prints what the hands did: the grabs and releases, the haptic pulses, and the state hash,
// which is the one `wedge replay SCENE RECORDING --hash` prints for the same files.
//   replay_recording SCENE.json RECORDING.jsonl
#include <cmath>
#include <cstdio>
#include <exception>

#include "wedge/recordings/recording.hpp"
#include "wedge/recordings/recording_source.hpp"
#include "wedge/scenes/interaction.hpp"
#include "wedge/scenes/scene.hpp"

int main(int argc, char** argv) {
  using namespace wedge;
  if (argc != 3) {
    std::fprintf(stderr, "usage: replay_recording SCENE.json RECORDING.jsonl\n");
    return 2;
  }
  try {
    const scenes::Scene<4> scene = scenes::load_scene_file<4>(argv[1]);
    World<4> world = scene.make_world(argv[1]);
    recordings::RecordingSource source({recordings::read_recording(argv[2])}, {argv[2]});
    input::Session<4> session(world, scenes::session_settings(scene, scene.timestep));

    // Step k starts at t = k h with the recording's hands at that time, up to the recording's end.
    const long steps = std::lround(std::ceil(source.duration() / session.timestep() - 1e-9));
    long grabs = 0, pulses = 0;
    for (long k = 0; k < steps; ++k) {
      session.step(source.frame_at(session.time()));
      for (const input::InteractionEvent<4>& e : session.events()) {
        const bool grab = e.kind == input::InteractionEvent<4>::Kind::Grab;
        grabs += grab;
        std::printf("%7.3f s  hand %d %s body %u\n", e.t, e.hand, grab ? "grabs" : "lets go of", e.body.index);
      }
      for (const input::HapticPulse<4>& p : session.pulses())
        std::printf("%7.3f s  pulse to hand %d, amplitude %.2f (bodies %u and %u met at %.2f m/s)\n", p.t, p.hand,
                    p.amplitude, p.held.index, p.other.index, p.approach_speed);
      pulses += long(session.pulses().size());
      session.clear_output();
    }
    std::printf("replayed %.3f s: %ld grabs, %ld haptic pulses; state hash %016llx\n", session.time(), grabs,
                pulses, static_cast<unsigned long long>(world.state_hash()));
    return 0;
  } catch (const std::exception& e) {  // scenes::SceneError, wedge::Error: one line naming the file
    std::fprintf(stderr, "replay_recording: %s\n", e.what());
    return 2;
  }
}
