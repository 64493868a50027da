// `wedge render`, run as a user would (support/cli_runner.hpp): a small 4D scene rendered to PNG frames
// (count, size, the body's own colour present, the background elsewhere), and bad input: exit code 2,
// one message naming the file, and no frames written. --sheet: one PNG grid of evenly picked frames, of
// the size its layout gives, each tile showing the body; a failed write leaves none of the run's files.
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

TEST_CASE("wedge render --sheet writes a contact sheet of evenly picked frames", "[cli][render]") {
  TempDir dir;
  dir.write("t.json", kTesseract);
  // 31 frames (steps 0, 2, .., 60): 12 tiles of 96 x 64, 4 to a row, 4-pixel borders.
  const Result r = dir.run("render t.json --steps 60 --every 2 --out frames --size 96x64 --sheet sheet.png");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("and a sheet of 12") != std::string::npos);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path() / "frames")) names.push_back(e.path().filename().string());
  CHECK(names.size() == 31);  // and no leftover .part files
  for (const std::string& n : names) CHECK(n.rfind("frame_", 0) == 0);
  const Image sheet = read_png(dir.path() / "sheet.png");
  CHECK(sheet.width == 4 + 4 * (96 + 4));
  CHECK(sheet.height == 4 + 3 * (64 + 4));
  for (int t = 0; t < 12; ++t) {
    const int x0 = 4 + (t % 4) * 100, y0 = 4 + (t / 4) * 68;
    long red = 0;
    for (int y = y0; y < y0 + 64; ++y)
      for (int x = x0; x < x0 + 96; ++x) {
        const std::size_t i = (std::size_t(y) * std::size_t(sheet.width) + std::size_t(x)) * 4;
        red += (sheet.rgba[i] > 2 * sheet.rgba[i + 1] + 20 && sheet.rgba[i] > 2 * sheet.rgba[i + 2] + 20) ? 1 : 0;
      }
    INFO("tile " << t);
    CHECK(red > 96 * 64 / 20);
    const std::size_t border = (std::size_t(y0 - 1) * std::size_t(sheet.width) + std::size_t(x0)) * 4;
    CHECK(sheet.rgba[border] == 40);
  }
  // The first tile is frame 0 exactly, box-filtered 1:1 below its label box.
  const Image first = read_png(dir.path() / "frames" / "frame_00000.png");
  for (int y = 20; y < 64; y += 7)
    for (int x = 0; x < 96; x += 5) {
      const std::size_t a = (std::size_t(y) * 96 + std::size_t(x)) * 4;
      const std::size_t b = (std::size_t(4 + y) * std::size_t(sheet.width) + std::size_t(4 + x)) * 4;
      REQUIRE(first.rgba[a] == sheet.rgba[b]);
    }
  // The sheet may go into the folder the run creates; fewer frames than tiles give one tile each.
  const Result r2 = dir.run("render t.json --steps 4 --every 2 --out new --size 96x64 --sheet new/s.png");
  INFO(r2.err);
  REQUIRE(r2.code == 0);
  const Image small = read_png(dir.path() / "new" / "s.png");
  CHECK(small.width == 4 + 3 * 100);
  CHECK(small.height == 4 + 68);
}

TEST_CASE("wedge render: a failed write removes the frames written so far, and a bad --sheet writes nothing",
          "[cli][render]") {
  TempDir dir;
  dir.write("t.json", kTesseract);
  // frame_00003.png is a folder: the fourth frame cannot be written.
  fs::create_directories(dir.path() / "frames" / "frame_00003.png");
  const Result r = dir.run("render t.json --steps 10 --every 2 --out frames --size 64x48 --sheet sheet.png");
  CHECK(r.code == 2);
  CHECK(r.err.rfind("wedge: ", 0) == 0);
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir.path() / "frames")) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"frame_00003.png"});
  CHECK(!fs::exists(dir.path() / "sheet.png"));

  for (const char* args : {"render t.json --steps 2 --out f --sheet nowhere/s.png",
                           "render t.json --steps 2 --out f --sheet ."}) {
    const Result b = dir.run(args);
    INFO(args << "\n" << b.err);
    CHECK(b.code == 2);
    CHECK(b.err.rfind("wedge: t.json: --sheet", 0) == 0);
    CHECK(!fs::exists(dir.path() / "f"));
  }
}

TEST_CASE("wedge render names the bodies that never meet the drawn slice", "[cli][render]") {
  TempDir dir;
  dir.write("t.json", kTesseract);
  const Result seen = dir.run("render t.json --steps 2 --out f --size 64x64");
  REQUIRE(seen.code == 0);
  CHECK(seen.err.empty());
  // The tesseract spans w in [-0.5, 0.5]; its turn in the xw plane widens that by far less than 1 m in two
  // steps, so x3 = 2 never meets it.
  const Result missed = dir.run("render t.json --steps 2 --w 2 --out g --size 64x64");
  REQUIRE(missed.code == 0);
  CHECK(missed.err == "wedge: warning: t.json: 't' never meets the drawn slice in any frame (move the slice with --w)\n");
}

TEST_CASE("wedge render --replay draws the scene as recordings drive it, the hand marked", "[cli][render][replay]") {
  TempDir dir;
  // A red tesseract floating at the origin (no gravity); a right hand grabs it at its centre and carries
  // it 1 m along +x in 1 s. Without the recording it stays put.
  dir.write("t.json", R"({"dim": 4, "bodies": [{"name": "t", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3, 0.3]},
    "color": [1, 0, 0]}]})");
  std::string rec = R"({"format":"wedge-recording","version":1,"source":"script","units":{"time":"s","position":"m",)"
                    R"("acceleration":"g","rotation_rate":"rad/s"},"conventions":{}})"
                    "\n";
  for (int i = 0; i <= 24; ++i) {
    const double t = i / 20.0, x = std::min(t, 1.0);
    rec += R"({"t":)" + std::to_string(t) + R"(,"type":"hand","hand":"right","position":[)" + std::to_string(x) +
           R"(,0,0],"orientation":[1,0,0,0],"squeeze":1,"trigger":0,"buttons":[],"mode4d":false})" + "\n";
  }
  dir.write("carry.jsonl", rec);
  auto centroid_x = [](const Image& img) {
    double sum = 0.0, count = 0.0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::uint8_t* p = &img.rgba[std::size_t(4 * (y * img.width + x))];
        if (p[0] > 2 * p[1] + 20 && p[0] > 2 * p[2] + 20) sum += x, count += 1;
      }
    REQUIRE(count > 20);
    return sum / count;
  };
  const Result r = dir.run("render t.json --replay carry.jsonl --steps 144 --every 144 --out frames --size 160x90");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const double moved = centroid_x(read_png(dir.path() / "frames" / "frame_00001.png")) -
                       centroid_x(read_png(dir.path() / "frames" / "frame_00000.png"));
  const Result still = dir.run("render t.json --steps 144 --every 144 --out still --size 160x90");
  REQUIRE(still.code == 0);
  const double stayed = centroid_x(read_png(dir.path() / "still" / "frame_00001.png")) -
                        centroid_x(read_png(dir.path() / "still" / "frame_00000.png"));
  INFO("moved " << moved << " px, stayed " << stayed << " px");
  CHECK(moved > 20.0);  // carried right across the picture
  CHECK(std::abs(stayed) < 1.0);
  // The hand is marked over the body it holds (green, view_overlays.hpp), and only in the replay.
  auto green_pixels = [](const Image& img) {
    int count = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4)
      count += img.rgba[i + 1] > img.rgba[i] + 50 && img.rgba[i + 1] > img.rgba[i + 2] + 50;
    return count;
  };
  const int held_mark = green_pixels(read_png(dir.path() / "frames" / "frame_00001.png"));
  INFO("green pixels: " << held_mark);
  CHECK(held_mark >= 4);
  CHECK(green_pixels(read_png(dir.path() / "still" / "frame_00001.png")) == 0);

  // A recording that does not fit the scene is refused before anything is drawn.
  dir.write("t3.json", R"({"dim": 3, "bodies": [{"name": "t", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]}}]})");
  std::string four = rec;
  for (std::size_t at = four.find("\"mode4d\":false"); at != std::string::npos; at = four.find("\"mode4d\":false"))
    four.replace(at, 14, "\"mode4d\":true");
  dir.write("four.jsonl", four);
  const Result bad = dir.run("render t3.json --replay four.jsonl --steps 10 --out bad");
  CHECK(bad.code == 2);
  CHECK(bad.err.find("four.jsonl") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.path() / "bad"));
}

// The joints are marked over the bodies (view_overlays.hpp): a bob on a rod hung from a point of the world
// and a door on a revolute hinge. With the marks the picture gains the rod (dark grey, between the pivot
// and the bob, so above the bob's own pixels) and the hinge's plane (blue); --no-joints leaves them out.
// The camera frames the anchors too (the pivot), with the marks or without.
TEST_CASE("wedge render marks the joints: the rod of a pendulum, a revolute joint's plane", "[cli][render]") {
  TempDir dir;
  const std::string bodies =
      R"({"name": "bob", "shape": {"type": "ball", "radius": 0.15}, "position": [0, -1, 0, 0], "color": [1, 0, 0]},
         {"name": "door", "shape": {"type": "box", "half_extents": [0.3, 0.4, 0.03, 0.03]}, "position": [1, -0.5, 0, 0],
          "color": [1, 0, 0]})";
  dir.write("joined.json", R"({"dim": 4, "bodies": [)" + bodies + R"(], "joints": [
      {"type": "distance", "body_b": "bob", "anchor_a": [0, 0, 0, 0]},
      {"type": "revolute", "body_b": "door", "anchor_a": [0.7, -0.5, 0, 0], "anchor_b": [-0.3, 0, 0, 0],
       "plane_a": [[1, 0, 0, 0], [0, 0, 1, 0]], "plane_b": [[1, 0, 0, 0], [0, 0, 1, 0]]}]})");
  dir.write("free.json", R"({"dim": 4, "bodies": [)" + bodies + "]}");
  const std::string view = R"( --steps 0 --size 320x240 --out )";
  const Result marked = dir.run("render joined.json" + view + "marked");
  INFO(marked.err);
  REQUIRE(marked.code == 0);
  REQUIRE(dir.run("render joined.json --no-joints" + view + "bare").code == 0);
  REQUIRE(dir.run("render free.json" + view + "free").code == 0);
  const Image with = read_png(dir.path() / "marked" / "frame_00000.png");
  const Image without = read_png(dir.path() / "bare" / "frame_00000.png");
  const Image free = read_png(dir.path() / "free" / "frame_00000.png");
  CHECK(without.rgba != free.rgba);  // (framed differently: the pivot 1 m above the bob)

  auto count = [](const Image& img, auto&& is) {
    int n = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4) n += is(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]) ? 1 : 0;
    return n;
  };
  auto blue = [](int r, int g, int b) { return b > r + 80 && b > g + 40; };
  const int blue_with = count(with, blue), blue_without = count(without, blue);
  // The rod: pixels darker in the marked picture than in the bare one, above the bob's topmost red pixel.
  int bob_top = with.height, rod = 0;
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width / 3; ++x) {  // (the bob is left of the door, which hangs at x = 1)
      const std::uint8_t* p = &without.rgba[std::size_t(4 * (y * with.width + x))];
      if (p[0] > 2 * p[1] + 20 && p[0] > 2 * p[2] + 20) bob_top = std::min(bob_top, y);
    }
  for (int y = 0; y < bob_top; ++y)
    for (int x = 0; x < with.width / 3; ++x) {
      const std::size_t i = std::size_t(4 * (y * with.width + x));
      rod += with.rgba[i] + 40 < without.rgba[i] && std::abs(int(with.rgba[i]) - int(with.rgba[i + 2])) < 30;
    }
  INFO("blue pixels " << blue_with << " (bare " << blue_without << "), rod pixels above the bob (row " << bob_top << "): " << rod);
  CHECK(bob_top < with.height);
  CHECK(blue_with >= 40);
  CHECK(blue_without == 0);
  CHECK(rod >= 20);
}
