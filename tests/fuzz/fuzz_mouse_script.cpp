// The viewer's --mouse script (JSON Lines of frames, buttons, tilts, slice offsets; view_mouse.hpp), read
// and checked against a 4D scene as `wedge view --mouse` does before any window opens.
#include "fuzz_input.hpp"
#include "view_mouse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "mouse.jsonl");
  fuzz::expect_success_or_refusal(path, [&] {
    const auto script = wedge::cli::viewer::read_mouse_script(path);
    wedge::cli::viewer::check_mouse_script<4>(script, path, "scene.json",
                                              [](const std::string& name) { return name == "tesseract"; });
  });
  return 0;
}
