// `wedge collide`, run as a user would. Expected values come from the geometry of the scenes (exact
// overlaps, analytic ball distances, axis-aligned bounding boxes computed here by hand), not from the
// engine. Depths and normals are exact up to round-off of O(1) numbers: 1e-12.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <sstream>

#include "cli_runner.hpp"

using namespace cli_runner;

namespace {

const char* kStack4 = R"({"dim": 4, "bodies": [
 {"name": "ground", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0, 0], "offset": 0}},
 {"name": "base", "shape": {"type": "box", "half_extents": [1, 1, 1, 1]}, "position": [0, 0.999, 0, 0]},
 {"name": "top", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}, "position": [0.8, 2.498, 0, 0.9]},
 {"name": "far", "shape": {"type": "ball", "radius": 0.5}, "position": [9, 9, 9, 9]}]})";

}  // namespace

TEST_CASE("wedge collide: a 4D stack on the ground, contact cells and a body far away", "[cli][collide]") {
  TempDir dir;
  dir.write("stack.json", kStack4);
  const Result r = dir.run("collide stack.json");
  REQUIRE(r.code == 0);
  const json doc = json::parse(r.out);
  REQUIRE(doc["pairs"].size() == 2);  // "far" overlaps nothing
  const json& ground = doc["pairs"][0];
  CHECK(ground["a"] == "ground");
  CHECK(ground["b"] == "base");
  CHECK(ground["intersecting"] == true);
  CHECK(ground["depth"].get<double>() == Approx(1e-3).margin(1e-12));
  CHECK(ground["normal"] == json::array({0.0, 1.0, 0.0, 0.0}));
  REQUIRE(ground["contacts"].size() == 8);  // the base's bottom cell, 2 x 2 x 2
  for (const json& c : ground["contacts"]) {
    CHECK(std::abs(c["point"][0].get<double>()) == Approx(1.0).margin(1e-12));
    CHECK(std::abs(c["point"][2].get<double>()) == Approx(1.0).margin(1e-12));
    CHECK(std::abs(c["point"][3].get<double>()) == Approx(1.0).margin(1e-12));
    CHECK(c["depth"].get<double>() == Approx(1e-3).margin(1e-12));
  }
  // The top cube overhangs the base in x and w: its contact cell is x in [0.3, 1], w in [0.4, 1].
  const json& stack = doc["pairs"][1];
  CHECK(stack["a"] == "base");
  CHECK(stack["b"] == "top");
  CHECK(stack["depth"].get<double>() == Approx(1e-3).margin(1e-12));
  REQUIRE(stack["contacts"].size() == 8);
  std::set<std::pair<double, double>> xw;
  for (const json& c : stack["contacts"])
    xw.insert({std::round(c["point"][0].get<double>() * 1e6) / 1e6, std::round(c["point"][3].get<double>() * 1e6) / 1e6});
  CHECK(xw == std::set<std::pair<double, double>>{{0.3, 0.4}, {0.3, 1.0}, {1.0, 0.4}, {1.0, 1.0}});
}

TEST_CASE("wedge collide: pairs are exactly those whose bounding boxes overlap, apart ones get -distance",
          "[cli][collide]") {
  // 40 axis-aligned boxes and balls in 3D: their bounding boxes are known without the engine.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-2.0, 2.0), size(0.1, 0.6);
  struct Item {
    bool ball;
    double c[3], h[3];
  };
  std::vector<Item> items;
  std::ostringstream scene;
  scene.precision(17);  // the file must hold exactly the numbers the test computes with
  scene << R"({"dim": 3, "bodies": [)";
  for (int i = 0; i < 40; ++i) {
    Item it{i % 2 == 0, {pos(rng), pos(rng), pos(rng)}, {size(rng), size(rng), size(rng)}};
    if (it.ball) it.h[1] = it.h[2] = it.h[0];
    items.push_back(it);
    scene << (i ? "," : "") << R"({"name": "b)" << i << R"(", "position": [)" << it.c[0] << "," << it.c[1] << ","
          << it.c[2] << "], ";
    if (it.ball)
      scene << R"("shape": {"type": "ball", "radius": )" << it.h[0] << "}}";
    else
      scene << R"("shape": {"type": "box", "half_extents": [)" << it.h[0] << "," << it.h[1] << "," << it.h[2] << "]}}";
  }
  scene << "]}";
  TempDir dir;
  dir.write("s.json", scene.str());
  const Result r = dir.run("collide s.json");
  REQUIRE(r.code == 0);
  const json doc = json::parse(r.out);
  std::set<std::pair<int, int>> expected, listed;
  for (int i = 0; i < 40; ++i)
    for (int j = i + 1; j < 40; ++j) {
      bool overlap = true;
      for (int k = 0; k < 3; ++k)
        overlap &= std::abs(items[i].c[k] - items[j].c[k]) <= items[i].h[k] + items[j].h[k];
      if (overlap) expected.insert({i, j});
    }
  for (const json& p : doc["pairs"]) {
    const int a = std::stoi(p["a"].get<std::string>().substr(1)), b = std::stoi(p["b"].get<std::string>().substr(1));
    listed.insert({a, b});
    if (items[a].ball && items[b].ball) {  // two balls: depth r_a + r_b - |c_b - c_a|, exactly
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) d2 += (items[b].c[k] - items[a].c[k]) * (items[b].c[k] - items[a].c[k]);
      const double depth = items[a].h[0] + items[b].h[0] - std::sqrt(d2);
      CHECK(p["depth"].get<double>() == Approx(depth).margin(1e-12));
      CHECK(p["intersecting"] == (depth >= 0.0));
    }
  }
  CHECK(expected.size() > 10);
  CHECK(listed == expected);
}

TEST_CASE("wedge collide: bad input exits with 2, names the file, writes nothing", "[cli][collide]") {
  TempDir dir;
  dir.write("stack.json", kStack4);
  dir.write("bad.json", R"({"dim": 4, "bodies": [{"name": "x", "shape": {"type": "box", "half_extents": [1, 1, 0, 1]}}]})");
  for (const std::string args : {"collide missing.json", "collide stack.json --margin -1",
                                 "collide stack.json --margin abc", "collide bad.json --out out.json"}) {
    INFO(args);
    const Result r = dir.run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("wedge: ", 0) == 0);
    CHECK(r.err.find(".json") != std::string::npos);
  }
  CHECK(!fs::exists(dir.path() / "out.json"));
  const Result ok = dir.run("collide stack.json --margin 0.01 --out out.json");
  CHECK(ok.code == 0);
  CHECK(json::parse(read_file(dir.path() / "out.json"))["pairs"].size() == 2);
}
