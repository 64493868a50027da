// A recording (docs/recording-format.md) replayed on the shipped toy table, as
// `wedge replay scenes/toy_table_4d.json RECORDING --until 0.05 --hash` does: the JSON Lines reader, the
// resampling into input frames, and the input layer's grabs, turns and gravity tilts on what it reads.
#include "fuzz_input.hpp"
#include "verbs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "recording.jsonl");
  wedge::cli::ReplayOptions o;
  o.scene = WEDGE_FUZZ_SCENE;
  o.recordings = {path};
  o.until = "0.05";
  o.hash = true;
  fuzz::expect_success_or_refusal(path, [&] { wedge::cli::run_replay(o); });
  return 0;
}
