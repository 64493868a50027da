// `wedge render`, run as a user would (support/cli_runner.hpp): a small 4D scene rendered to PNG frames
// (count, size, the body's own colour present, the background elsewhere), and bad input: exit code 2,
// one message naming the file, and no frames written.
#include <png.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace {

using namespace cli_runner;

// A red tesseract of side 1 at the origin, seen by the default camera.
const char* kTesseract = R"({"dim": 4, "bodies": [{"name": "t", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]},
  "color": [1, 0, 0], "angular_velocity": [0, 0, 1, 0, 0, 0]}]})";

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

Image read_png(const fs::path& p) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&img, p.string().c_str()) != 0);
  img.format = PNG_FORMAT_RGBA;
  Image out;
  out.width = int(img.width);
  out.height = int(img.height);
  out.rgba.resize(PNG_IMAGE_SIZE(img));
  REQUIRE(png_image_finish_read(&img, nullptr, out.rgba.data(), 0, nullptr) != 0);
  return out;
}

}  // namespace

TEST_CASE("wedge render writes one PNG per drawn step with the body in its colour", "[cli][render]") {
  TempDir dir;
  dir.write("t.json", kTesseract);
  const Result r = dir.run("render t.json --steps 2 --every 2 --out frames --size 96x64");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());  // no progress bar when stderr is not a terminal
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path() / "frames")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  REQUIRE(names == std::vector<std::string>{"frame_00000.png", "frame_00001.png"});
  for (const std::string& name : names) {
    const Image img = read_png(dir.path() / "frames" / name);
    REQUIRE(img.width == 96);
    REQUIRE(img.height == 64);
    // The lit red body: red well above green and blue; it fills a fair part of the picture (the camera
    // frames it) but not all of it.
    long red = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4)
      red += (img.rgba[i] > 2 * img.rgba[i + 1] + 20 && img.rgba[i] > 2 * img.rgba[i + 2] + 20) ? 1 : 0;
    CHECK(red > 96 * 64 / 20);
    CHECK(red < 96 * 64 / 2);
  }
}

TEST_CASE("wedge render: bad input exits 2 naming the file and writes no frames", "[cli][render]") {
  TempDir dir;
  dir.write("t.json", kTesseract);
  dir.write("flat.json", R"({"dim": 2, "bodies": []})");
  dir.write("badcolor.json", R"({"dim": 4, "bodies": [{"shape": {"type": "ball", "radius": 1}, "color": [1, 2, 0]}]})");
  dir.write("badview.json", R"({"dim": 4, "view": {"eye": [0, 0, 1], "zoom": 2}, "bodies": []})");
  struct Case {
    const char* args;
    const char* message;
  };
  for (const Case& c : {Case{"render t.json --steps 2", "t.json: --out DIR is required"},
                        Case{"render t.json --steps -1 --out f", "t.json: --steps"},
                        Case{"render t.json --steps 2 --out f --size 100", "t.json: --size"},
                        Case{"render t.json --steps 2 --out f --size 10x10", "t.json: --size"},
                        Case{"render t.json --steps 2 --out f --w abc", "t.json: --w"},
                        Case{"render t.json --steps 2 --out f --w 0,1", "t.json: --w takes at most 1"},
                        Case{"render t.json --steps 2 --out f --subdivisions 0", "t.json: --subdivisions"},
                        Case{"render flat.json --steps 2 --out f", "flat.json: a 2D scene cannot be rendered"},
                        Case{"render badcolor.json --steps 2 --out f", "badcolor.json: bodies[0].color"},
                        Case{"render badview.json --steps 2 --out f", "badview.json: view"},
                        Case{"render missing.json --steps 2 --out f", "missing.json"}}) {
    const Result r = dir.run(c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind(std::string("wedge: ") + c.message, 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!fs::exists(dir.path() / "f"));
  }
}
