// A recording (docs/recording-format.md) replayed on the shipped toy table for 0.05 s, as
// `wedge replay scenes/toy_table_4d.json RECORDING --until 0.05 --hash` replays it: the JSON Lines reader,
// the check that its hands fit the scene, the resampling into input frames, and the input layer's grabs,
// turns and gravity tilts on what it reads, in the world's steps. The scene, which is not the input, is
// loaded once (loading it is most of a run otherwise); each input gets a fresh world made from it.
#include "fuzz_input.hpp"
#include "replay_input.hpp"

namespace {

const wedge::scenes::Scene<4>& toy_table() {
  static const wedge::scenes::Scene<4> scene = wedge::scenes::load_scene_file<4>(WEDGE_FUZZ_SCENE);
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "recording.jsonl");
  const wedge::scenes::Scene<4>& scene = toy_table();
  fuzz::expect_success_or_refusal(path, [&] {
    wedge::World<4> world = scene.make_world(WEDGE_FUZZ_SCENE);
    wedge::cli::ReplayInput<4> replay(scene, world, {path}, WEDGE_FUZZ_SCENE, scene.timestep);
    while (replay.session().time() < 0.05) replay.step();
    volatile std::uint64_t hash = world.state_hash();
    (void)hash;
  });
  return 0;
}
