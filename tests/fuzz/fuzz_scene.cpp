// Scene JSON (docs/scene-format.md), as `wedge simulate SCENE --steps 8 --hash` reads and runs it: the
// loader, every shape kind (meshes and hulls through Qhull included), the world's checks, a few steps.
#include "fuzz_input.hpp"
#include "verbs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "scene.json");
  wedge::cli::SimulateOptions o;
  o.scene = path;
  o.steps = "8";
  o.hash = true;
  fuzz::expect_success_or_refusal(path, [&] { wedge::cli::run_simulate(o); });
  return 0;
}
