// Shape JSON with its density or mass (`wedge inertia FILE`): boxes, balls, polytopes, simplex meshes
// (docs/scene-format.md), their mass properties and principal frame.
#include "fuzz_input.hpp"
#include "verbs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "shape.json");
  wedge::cli::InertiaOptions o;
  o.file = path;
  fuzz::expect_success_or_refusal(path, [&] { wedge::cli::run_inertia(o); });
  return 0;
}
