// The `wedge` program, run as a user would: input files written to a temporary folder, the binary run
// through the shell, stdout, stderr and the exit code checked.
//
// Tolerances: a box's mass properties are closed forms of a few products, so they match the formulas to
// round-off (1e-12 relative). The projectile runs symplectic Euler with constant gravity, whose discrete
// solution is exact: v_n = v0 + n h g, x_n = x0 + n h v0 + h^2 g n (n + 1) / 2; over 100 steps of numbers
// of order 10 the accumulated round-off stays below 1e-12, so 1e-9 absolute separates it from any
// wrong formula (the continuous x0 + v0 t + g t^2 / 2 differs by h^2 g n / 2 ~ 5e-2 at n = 100).
#include <catch2/catch.hpp>

#include <csignal>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "fp_traps.hpp"
#include "wedge/contact.hpp"

namespace {

using namespace cli_runner;
namespace fs = std::filesystem;
using nlohmann::json;

bool close_rel(double a, double b, double rel) { return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)); }

const char* kBox4 = R"({"dim": 4, "shape": {"type": "box", "half_extents": [0.55, 0.15, 1.25, 0.35]}, "density": 2.5})";

const char* kProjectile3 = R"({"dim": 3, "gravity": [0.5, -9.81, 0.25], "timestep": 0.01,
  "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "position": [1, 2, -3],
              "velocity": [3, 12, -1], "mass": 0.5},
             {"name": "box", "shape": {"type": "box", "half_extents": [0.3, 0.2, 0.1]},
              "velocity": [0, 1, 0], "angular_velocity": [0.1, 5, 0.1]}]})";

}  // namespace

TEST_CASE("wedge --help lists the verbs, every verb has --help", "[cli]") {
  TempDir dir;
  const Result top = dir.run("--help");
  CHECK(top.code == 0);
  CHECK(top.out.find("inertia") != std::string::npos);
  CHECK(top.out.find("simulate") != std::string::npos);
  for (const char* verb : {"inertia", "simulate"}) {
    const Result r = dir.run(std::string(verb) + " --help");
    CHECK(r.code == 0);
    CHECK(r.out.find(std::string("wedge ") + verb) != std::string::npos);
  }
  CHECK(dir.run("simulate --help").out.find("--steps") != std::string::npos);
}

TEST_CASE("wedge inertia of a 4D box: volume, mass, I_(ij) = m (a_i^2 + a_j^2) / 12, principal frame", "[cli]") {
  TempDir dir;
  dir.write("box.json", kBox4);
  const Result r = dir.run("inertia box.json");
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  const json j = json::parse(r.out);
  const double a[4] = {1.1, 0.3, 2.5, 0.7};  // full side lengths
  const double volume = a[0] * a[1] * a[2] * a[3], mass = 2.5 * volume;
  CHECK(j.at("dim") == 4);
  CHECK(close_rel(j.at("volume").get<double>(), volume, 1e-12));
  CHECK(close_rel(j.at("mass").get<double>(), mass, 1e-12));
  REQUIRE(j.at("center").size() == 4);
  for (const auto& c : j.at("center")) CHECK(std::abs(c.get<double>()) < 1e-12);

  const json& inertia = j.at("inertia");
  REQUIRE(inertia.size() == 6);
  int row = 0;
  std::vector<double> expected;
  for (int i = 0; i < 4; ++i)
    for (int k = i + 1; k < 4; ++k, ++row) {
      REQUIRE(inertia[row].size() == 6);
      const double want = mass * (a[i] * a[i] + a[k] * a[k]) / 12.0;
      expected.push_back(want);
      for (int col = 0; col < 6; ++col) {
        const double got = inertia[row][col].get<double>();
        if (col == row)
          CHECK(close_rel(got, want, 1e-12));
        else
          CHECK(std::abs(got) <= 1e-12 * want);
      }
    }

  // Principal axes: an orthonormal n x n matrix; principal inertia diagonal with the same moments.
  const json& axes = j.at("principal_axes");
  REQUIRE(axes.size() == 4);
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q) {
      double d = 0.0;
      for (int r2 = 0; r2 < 4; ++r2) d += axes[r2][p].get<double>() * axes[r2][q].get<double>();
      CHECK(std::abs(d - (p == q ? 1.0 : 0.0)) < 1e-12);
    }
  const json& principal = j.at("principal_inertia");
  REQUIRE(principal.size() == 6);
  std::vector<double> diagonal;
  for (int p = 0; p < 6; ++p) {
    REQUIRE(principal[p].size() == 6);
    for (int q = 0; q < 6; ++q)
      if (p != q) CHECK(principal[p][q].get<double>() == 0.0);
    diagonal.push_back(principal[p][p].get<double>());
  }
  std::sort(diagonal.begin(), diagonal.end());
  std::sort(expected.begin(), expected.end());
  for (int p = 0; p < 6; ++p) CHECK(close_rel(diagonal[p], expected[p], 1e-12));
}

TEST_CASE("wedge inertia: the shipped tesseract and a mesh simplex", "[cli]") {
  TempDir dir;
  const Result r = dir.run("inertia '" WEDGE_SOURCE_DIR "/scenes/inertia_tesseract.json'");
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  CHECK(close_rel(j.at("volume").get<double>(), 1.0, 1e-12));
  CHECK(close_rel(j.at("inertia")[0][0].get<double>(), 1.0 / 6.0, 1e-12));

  // The corner 3-simplex {0, e0, e1, e2}: volume 1/6, centre (1/4, 1/4, 1/4), with "mass" instead of a density.
  dir.write("simplex.json", R"({"dim": 3, "mass": 3.0, "shape": {"type": "mesh",
    "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "cells": [[0,2,1],[0,1,3],[0,3,2],[1,2,3]]}})");
  const Result s = dir.run("inertia simplex.json");
  REQUIRE(s.code == 0);
  const json k = json::parse(s.out);
  CHECK(close_rel(k.at("volume").get<double>(), 1.0 / 6.0, 1e-12));
  CHECK(close_rel(k.at("mass").get<double>(), 3.0, 1e-12));
  for (const auto& c : k.at("center")) CHECK(close_rel(c.get<double>(), 0.25, 1e-12));
}

TEST_CASE("wedge inertia: regular 4-polytopes by name, and their bad input", "[cli]") {
  TempDir dir;
  // The 24-cell's edge equals its circumradius R and its 4-volume is 2 a^4 (Coxeter, Regular
  // Polytopes, table I): R = 0.9 gives V = 1.3122, mass 2.6244 at density 2. The hull has 24 octahedral
  // cells of 4 tetrahedra each; round-off 1e-15, checked to 1e-12 relative.
  dir.write("c24.json", R"({"dim": 4, "shape": {"type": "regular_polytope", "polytope": "24-cell", "circumradius": 0.9},
    "density": 2.0})");
  const Result r = dir.run("inertia c24.json");
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  CHECK(close_rel(j.at("volume").get<double>(), 2.0 * std::pow(0.9, 4), 1e-12));
  CHECK(close_rel(j.at("mass").get<double>(), 4.0 * std::pow(0.9, 4), 1e-12));
  for (const auto& c : j.at("center")) CHECK(std::abs(c.get<double>()) < 1e-12);

  const std::pair<const char*, const char*> cases[] = {
      {R"({"dim": 4, "shape": {"type": "regular_polytope", "polytope": "7-cell", "circumradius": 1}})",
       "shape.polytope: unknown regular polytope \"7-cell\""},
      {R"({"dim": 3, "shape": {"type": "regular_polytope", "polytope": "tesseract", "circumradius": 1}})",
       "shape.type: regular polytopes exist only in 4D here (this scene is 3D)"},
      {R"({"dim": 4, "shape": {"type": "regular_polytope", "polytope": "16-cell", "circumradius": -1}})",
       "shape.circumradius: the circumradius must be positive"},
      {R"({"dim": 4, "shape": {"type": "regular_polytope", "polytope": "16-cell"}})", "circumradius"},
      {R"({"dim": 4, "shape": {"type": "regular_polytope", "polytope": "16-cell", "circumradius": 1, "edge": 1}})",
       "shape.edge"},
  };
  for (const auto& [scene, message] : cases) {
    INFO(scene);
    dir.write("bad.json", scene);
    const Result e = dir.run("inertia bad.json");
    INFO(e.err);
    CHECK(e.code == 2);
    CHECK(e.out.empty());
    CHECK(e.err.find("bad.json") != std::string::npos);
    CHECK(e.err.find(message) != std::string::npos);
    CHECK(std::count(e.err.begin(), e.err.end(), '\n') == 1);
  }
}

TEST_CASE("wedge simulate: a 3D projectile follows the discrete symplectic-Euler solution", "[cli]") {
  TempDir dir;
  dir.write("projectile.json", kProjectile3);
  const Result r = dir.run("simulate projectile.json --steps 100");
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  const std::vector<json> lines = r.lines();
  REQUIRE(lines.size() == 101);
  const double h = 0.01, g[3] = {0.5, -9.81, 0.25}, x0[3] = {1, 2, -3}, v0[3] = {3, 12, -1};
  const int k = wedge::ContactSettings{}.substeps;  // each step is k sub-steps of symplectic Euler of h / k
  const double hs = h / k;
  for (int n = 0; n <= 100; ++n) {
    const json& line = lines[n];
    CHECK(line.at("step") == n);
    CHECK(std::abs(line.at("time").get<double>() - n * h) < 1e-12);
    CHECK(line.at("energy").is_number());
    CHECK(line.at("linear_momentum").size() == 3);
    CHECK(line.at("angular_momentum").size() == 3);  // k = 3
    REQUIRE(line.at("bodies").size() == 2);
    const json& ball = line.at("bodies")[0];
    CHECK(ball.at("name") == "ball");
    CHECK(ball.at("rotor").size() == 4);  // 2^(n-1)
    CHECK(ball.at("angular_velocity").size() == 3);
    CHECK(ball.at("angular_momentum").size() == 3);
    for (int i = 0; i < 3; ++i) {
      const double m = double(n) * k;
      const double x = x0[i] + v0[i] * n * h + g[i] * hs * hs * m * (m + 1) / 2.0;
      CHECK(std::abs(ball.at("position")[i].get<double>() - x) < 1e-9);
      CHECK(std::abs(ball.at("velocity")[i].get<double>() - (v0[i] + g[i] * n * h)) < 1e-9);
      // Momentum of both bodies: p = sum m (v0 + n h g); the box has v0 = (0, 1, 0).
      const json& box = line.at("bodies")[1];
      const double m_box = 0.6 * 0.4 * 0.2;  // density 1: mass = volume
      const double p = 0.5 * ball.at("velocity")[i].get<double>() + m_box * box.at("velocity")[i].get<double>();
      CHECK(std::abs(line.at("linear_momentum")[i].get<double>() - p) < 1e-12);
    }
  }
  // Same run, same bits.
  CHECK(dir.run("simulate projectile.json --steps 100").out == r.out);
}

TEST_CASE("wedge simulate: --every, --out, --hash and --dt", "[cli]") {
  TempDir dir;
  dir.write("projectile.json", kProjectile3);

  SECTION("--every K writes step 0 and the multiples of K") {
    const Result r = dir.run("simulate projectile.json --steps 10 --every 3");
    REQUIRE(r.code == 0);
    const std::vector<json> lines = r.lines();
    REQUIRE(lines.size() == 4);
    for (int i = 0; i < 4; ++i) CHECK(lines[i].at("step") == 3 * i);
    CHECK(dir.run("simulate projectile.json --steps 12 --every 4").lines().size() == 4);
    CHECK(dir.run("simulate projectile.json --steps 0").lines().size() == 1);
  }
  SECTION("--out writes the file, and stdout says only where the states went") {
    const Result r = dir.run("simulate projectile.json --steps 5 --out run.jsonl");
    REQUIRE(r.code == 0);
    CHECK(r.out == "wrote 6 states (steps 0..5) to run.jsonl\n");
    const std::string text = read_file(dir.path() / "run.jsonl");
    CHECK(std::count(text.begin(), text.end(), '\n') == 6);
    CHECK(text == dir.run("simulate projectile.json --steps 5").out);
    CHECK(dir.listing() == std::vector<std::string>{"projectile.json", "run.jsonl"});  // no temporary left
  }
  SECTION("--hash appends the final state hash, the same on every run") {
    const Result r = dir.run("simulate projectile.json --steps 20 --hash");
    REQUIRE(r.code == 0);
    const std::vector<json> lines = r.lines();
    REQUIRE(lines.size() == 22);
    const std::string hash = lines.back().at("state_hash");
    CHECK(hash.size() == 16);
    CHECK(hash.find_first_not_of("0123456789abcdef") == std::string::npos);
    CHECK(dir.run("simulate projectile.json --steps 20 --hash").out == r.out);
    CHECK(dir.run("simulate projectile.json --steps 21 --hash").lines().back().at("state_hash") != hash);
  }
  SECTION("--workers 2 writes the same states, bit for bit, as one thread") {
    // (The shipped 3D pyramid, 211 boxes: big enough that its largest colours are split.)
    const std::string scene = std::string(WEDGE_SOURCE_DIR) + "/scenes/pyramid_3d.json";
    const Result one = dir.run("simulate " + scene + " --steps 60 --every 20 --hash");
    REQUIRE(one.code == 0);
    CHECK(dir.run("simulate " + scene + " --steps 60 --every 20 --hash --workers 2").out == one.out);
  }
  SECTION("--dt overrides the scene's timestep") {
    const std::vector<json> lines = dir.run("simulate projectile.json --steps 4 --dt 0.025").lines();
    REQUIRE(lines.size() == 5);
    CHECK(std::abs(lines[4].at("time").get<double>() - 0.1) < 1e-15);
  }
}

TEST_CASE("wedge simulate: every shipped scene runs", "[cli]") {
  TempDir dir;
  int count = 0;
  for (const auto& e : fs::directory_iterator(fs::path(WEDGE_SOURCE_DIR) / "scenes")) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".json" || name.rfind("inertia_", 0) == 0 || name == "hashes.json") continue;
    INFO(name);
    const Result r = dir.run("simulate '" + e.path().string() + "' --steps 10");
    CHECK(r.code == 0);
    CHECK(r.err.empty());
    CHECK(r.lines().size() == 11);
    CHECK(r.out.find("null") == std::string::npos);
    ++count;
  }
  CHECK(count >= 8);
}

TEST_CASE("wedge: bad input exits with 2, names the file, writes nothing", "[cli]") {
  struct Case {
    const char* what;
    const char* scene;      // nullptr: no file written
    const char* args;       // after "simulate bad.json"
    const char* message;    // expected in stderr besides the file name
  };
  const Case cases[] = {
      {"missing file", nullptr, "--steps 1", "cannot open"},
      {"malformed JSON", R"({"dim": 3, "bodies": [)", "--steps 1", "line 1, column"},
      {"top level not an object", "[1, 2]", "--steps 1", "object"},
      {"wrong array size", R"({"dim": 4, "bodies": [{"shape": {"type": "box", "half_extents": [1, 1, 1]}}]})",
       "--steps 1", "bodies[0].shape.half_extents: expected 4 numbers, got 3"},
      {"wrong vector size", R"({"dim": 3, "gravity": [0, -9.81], "bodies": []})", "--steps 1", "gravity"},
      {"wrong bivector size", R"({"dim": 4, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "angular_velocity": [1, 2, 3]}]})",
       "--steps 1", "bodies[0].angular_velocity: expected 6 numbers, got 3"},
      {"dim too large", R"({"dim": 7, "bodies": []})", "--steps 1", "dim"},
      {"dim too small", R"({"dim": 1, "bodies": []})", "--steps 1", "dim"},
      {"dim missing", R"({"bodies": []})", "--steps 1", "dim"},
      {"unknown top-level key", R"({"dim": 3, "bodies": [], "gravty": [0, 0, 0]})", "--steps 1", "gravty"},
      {"unknown body key", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "colour": "red"}]})",
       "--steps 1", "bodies[0].colour"},
      {"unknown shape key", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1, "r": 2}}]})",
       "--steps 1", "bodies[0].shape.r"},
      {"unknown shape type", R"({"dim": 3, "bodies": [{"shape": {"type": "torus"}}]})", "--steps 1", "torus"},
      {"unknown gyroscopic method", R"({"dim": 3, "gyroscopic_method": "rk4", "bodies": []})", "--steps 1",
       "gyroscopic_method: must be \"midpoint\" or \"euler\""},
      {"wrong type", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": "1"}}]})", "--steps 1",
       "bodies[0].shape.radius: expected a number"},
      {"wrong type for a flag", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "static": 1}]})",
       "--steps 1", "bodies[0].static"},
      {"open mesh", R"({"dim": 3, "bodies": [{"shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
         "cells": [[0,2,1],[0,1,3],[0,3,2]]}}]})", "--steps 1", "bodies[0].shape"},
      {"inside-out mesh", R"({"dim": 3, "bodies": [{"shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
         "cells": [[0,1,2],[0,3,1],[0,2,3],[1,3,2]]}}]})", "--steps 1", "bodies[0].shape"},
      {"degenerate mesh", R"({"dim": 3, "bodies": [{"shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],
         "cells": [[0,2,1],[0,1,3],[0,3,2],[1,2,3]]}}]})", "--steps 1", "bodies[0].shape"},
      {"mesh index out of range", R"({"dim": 3, "bodies": [{"shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
         "cells": [[0,2,1],[0,1,3],[0,3,2],[1,2,7]]}}]})", "--steps 1", "bodies[0].shape.cells[3][2]"},
      {"flat polytope", R"({"dim": 3, "bodies": [{"shape": {"type": "polytope", "vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}}]})",
       "--steps 1", "bodies[0].shape"},
      {"zero density", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "density": 0}]})", "--steps 1",
       "bodies[0].density"},
      {"negative density", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "density": -2}]})",
       "--steps 1", "bodies[0].density"},
      {"zero mass", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "mass": 0}]})", "--steps 1",
       "bodies[0].mass"},
      {"negative size", R"({"dim": 3, "bodies": [{"shape": {"type": "box", "half_extents": [1, -1, 1]}}]})",
       "--steps 1", "bodies[0].shape"},
      {"non-finite number", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1e999}}]})", "--steps 1",
       "overflow"},
      {"not a rotor", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "rotor": [1, 0.1, 0, 0]}]})",
       "--steps 1", "bodies[0].rotor"},
      {"restitution above 1", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "restitution": 1.5}]})",
       "--steps 1", "bodies[0].restitution"},
      {"negative friction", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "friction": -0.1}]})",
       "--steps 1", "bodies[0].friction"},
      {"dynamic halfspace", R"({"dim": 3, "bodies": [{"shape": {"type": "halfspace", "normal": [0, 1, 0], "offset": 0}}]})",
       "--steps 1", "static"},
      {"static and kinematic", R"({"dim": 3, "bodies": [{"shape": {"type": "sphere", "radius": 1}, "static": true, "kinematic": true}]})",
       "--steps 1", "bodies[0]"},
      {"duplicate names", R"({"dim": 2, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}},
         {"name": "a", "shape": {"type": "sphere", "radius": 1}}]})", "--steps 1", "bodies[1]"},
      {"negative shock tolerance", R"({"dim": 2, "contact": {"shock_tolerance": -1e-6}, "bodies": []})", "--steps 1",
       "contact.shock_tolerance"},
      {"negative contact tolerance", R"({"dim": 2, "contact": {"contact_tolerance": -1}, "bodies": []})", "--steps 1",
       "contact.contact_tolerance"},
      {"negative contact iterations", R"({"dim": 2, "contact": {"contact_iterations": -1}, "bodies": []})",
       "--steps 1", "contact.contact_iterations"},
      {"unknown contact key", R"({"dim": 2, "contact": {"shock_tol": 1}, "bodies": []})", "--steps 1", "contact.shock_tol"},
      {"unknown solver", R"({"dim": 2, "contact": {"solver": "tgs"}, "bodies": []})", "--steps 1",
       "contact.solver: must be \"soft_step\" or \"paper\""},
      {"zero substeps", R"({"dim": 2, "contact": {"substeps": 0}, "bodies": []})", "--steps 1", "contact.substeps"},
      {"joint to an unknown body", R"({"dim": 2, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}],
         "joints": [{"type": "point", "body_b": "b"}]})", "--steps 1", "joints[0].body_b: no body is named \"b\""},
      {"joint of an unknown type", R"({"dim": 2, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}],
         "joints": [{"type": "hinge", "body_b": "a"}]})", "--steps 1", "joints[0].type: must be \"point\", \"distance\", \"revolute\", \"prismatic\" or \"weld\""},
      {"joint anchor far from its body", R"({"dim": 3, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "point", "body_b": "a", "anchor_b": [5, 0, 0]}]})", "--steps 1",
       "joints[0].anchor_b: is 4.9 m outside body \"a\""},
      {"rope shorter than its minimum", R"({"dim": 2, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "distance", "body_b": "a", "anchor_a": [0, 1], "spring": true, "min_length": 2,
         "max_length": 1}]})", "--steps 1", "joints[0].max_length: must be >= min_length"},
      {"limits without a spring", R"({"dim": 2, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "distance", "body_b": "a", "anchor_a": [0, 1], "max_length": 1}]})", "--steps 1",
       "joints[0]: frequency, damping_ratio, min_length and max_length are a spring's"},
      {"joint of two static bodies", R"({"dim": 2, "bodies": [{"name": "a", "static": true, "shape": {"type": "sphere", "radius": 1}},
         {"name": "b", "static": true, "shape": {"type": "sphere", "radius": 1}}],
         "joints": [{"type": "point", "body_a": "a", "body_b": "b"}]})", "--steps 1", "joints[0]: add_joint: neither body is dynamic"},
      {"revolute plane not orthonormal", R"({"dim": 4, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "revolute", "body_b": "a", "plane_a": [[1, 0, 0, 0], [1, 1, 0, 0]]}]})", "--steps 1",
       "joints[0]: add_joint: plane_u_a and plane_v_a must be orthonormal"},
      {"revolute planes apart", R"({"dim": 4, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "revolute", "body_b": "a", "plane_b": [[1, 0, 0, 0], [0, 0, 1, 0]]}]})", "--steps 1",
       "joints[0]: add_joint: the revolute joint's planes of body_a and body_b are not the same plane"},
      {"revolute limits the wrong way", R"({"dim": 3, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "revolute", "body_b": "a", "lower_angle": 1, "upper_angle": -1}]})", "--steps 1",
       "joints[0].upper_angle: must be >= lower_angle"},
      {"prismatic axis zero", R"({"dim": 4, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "prismatic", "body_b": "a", "axis": [0, 0, 0, 0]}]})", "--steps 1",
       "joints[0].axis: must be a direction, not zero"},
      {"prismatic limits the wrong way", R"({"dim": 4, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "prismatic", "body_b": "a", "lower_translation": 0.5, "upper_translation": 0.2}]})",
       "--steps 1", "joints[0].upper_translation: must be >= lower_translation"},
      {"prismatic motor force negative", R"({"dim": 4, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "prismatic", "body_b": "a", "motor": true, "max_motor_force": -1}]})", "--steps 1",
       "joints[0].max_motor_force"},
      {"joints under the paper's solver", R"({"dim": 2, "contact": {"solver": "paper"},
         "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}],
         "joints": [{"type": "point", "body_b": "a"}]})", "--steps 1", "joints: the paper's contact solver"},
      {"negative contact hertz", R"({"dim": 2, "contact": {"contact_hertz": -30}, "bodies": []})", "--steps 1",
       "contact.contact_hertz"},
      {"negative recycle distance", R"({"dim": 2, "contact": {"recycle_distance": -0.1}, "bodies": []})", "--steps 1",
       "contact.recycle_distance"},
      {"timestep not positive", R"({"dim": 2, "timestep": 0, "bodies": []})", "--steps 1", "timestep"},
      {"steps negative", R"({"dim": 2, "bodies": []})", "--steps -1", "--steps"},
      {"steps missing", R"({"dim": 2, "bodies": []})", "", "--steps"},
      {"steps not a number", R"({"dim": 2, "bodies": []})", "--steps ten", "--steps"},
      {"dt zero", R"({"dim": 2, "bodies": []})", "--steps 1 --dt 0", "--dt"},
      {"dt negative", R"({"dim": 2, "bodies": []})", "--steps 1 --dt=-0.01", "--dt"},
      {"every zero", R"({"dim": 2, "bodies": []})", "--steps 1 --every 0", "--every"},
      {"workers zero", R"({"dim": 2, "bodies": []})", "--steps 1 --workers 0", "--workers must be an integer in 1..64"},
      {"workers not a number", R"({"dim": 2, "bodies": []})", "--steps 1 --workers two", "--workers must be an integer"},
      {"dt too large", R"({"dim": 2, "bodies": []})", "--steps 1 --dt 1e10", "--dt must be a step size in [1e-6, 0.1] s"},
      {"dt too small", R"({"dim": 2, "bodies": []})", "--steps 1 --dt 1e-9", "--dt"},
      {"timestep too large", R"({"dim": 2, "timestep": 1, "bodies": []})", "--steps 1", "timestep: must be in"},
      {"duplicate top-level key", R"({"dim": 4, "dim": 5, "bodies": []})", "--steps 1", "duplicate key 'dim'"},
      {"duplicate nested key", R"({"dim": 3, "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}},
         {"name": "b", "shape": {"type": "sphere", "type": "box", "radius": 1}}]})", "--steps 1",
       "bodies[1].shape: duplicate key 'type'"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    TempDir dir;
    if (c.scene) dir.write("bad.json", c.scene);
    for (const bool to_file : {false, true}) {
      const Result r = dir.run(std::string("simulate bad.json ") + c.args + (to_file ? " --out out.jsonl" : ""));
      INFO(r.err);
      CHECK(r.code == 2);
      CHECK(r.out.empty());
      CHECK(r.err.find("bad.json") != std::string::npos);
      CHECK(r.err.find(c.message) != std::string::npos);
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
      CHECK(!fs::exists(dir.path() / "out.jsonl"));
      CHECK(dir.listing().size() == (c.scene ? 1u : 0u));  // no temporary files left behind
    }
  }
}

// A run that overflows: as users run it, the program names the body and the quantity (exit 2); with
// floating-point traps on (WEDGE_FP_TRAPS=1, as every other CLI test runs it) the first overflowing
// operation stops it with SIGFPE (a shell's 128 + 8), at its source.
TEST_CASE("wedge simulate: a state that overflows is named, or trapped at its source with WEDGE_FP_TRAPS=1", "[cli]") {
  struct Case {
    const char* what;
    const char* scene;
    const char* args;
    const char* message;
  };
  const Case cases[] = {
      {"total energy overflows", R"({"dim": 3, "bodies": [{"name": "rocket", "shape": {"type": "sphere", "radius": 1},
         "velocity": [1e200, 0, 0]}]})", "--steps 1", "energy overflowed to a non-finite value at step 0 (the fastest body is 'rocket' at 1e+200 m/s;"},
      {"state overflows", R"({"dim": 3, "gravity": [1e308, 0, 0], "bodies": [{"name": "stone",
         "shape": {"type": "sphere", "radius": 1}}]})", "--steps 100 --every 1000 --dt 0.1",
       "non-finite position of body 'stone' at step 18"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    TempDir dir;
    dir.write("bad.json", c.scene);
    const Result r = dir.shell(std::string("WEDGE_FP_TRAPS=0 $WEDGE simulate bad.json ") + c.args);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("wedge: bad.json: ", 0) == 0);
    CHECK(r.err.find(c.message) != std::string::npos);
    if (fp_traps::requested()) CHECK(dir.run(std::string("simulate bad.json ") + c.args).code == 128 + SIGFPE);
  }
}

TEST_CASE("wedge inertia: bad input exits with 2 and names the file", "[cli]") {
  TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {R"({"dim": 4, "shape": {"type": "box", "half_extents": [1, 1]}})", "shape.half_extents"},
      {R"({"dim": 4, "shape": {"type": "sphere", "radius": 1}, "density": -1})", "density"},
      {R"({"dim": 4, "shape": {"type": "sphere", "radius": 1}, "extra": 1})", "extra"},
      {R"({"dim": 3, "shape": {"type": "halfspace", "normal": [0, 1, 0], "offset": 0}})", "shape"},
      {R"({"dim": 9, "shape": {"type": "sphere", "radius": 1}})", "dim"},
      {R"({"dim": 4, "shape": )", "malformed"},
  };
  for (const auto& [scene, message] : cases) {
    INFO(scene);
    dir.write("in.json", scene);
    const Result r = dir.run("inertia in.json");
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find("in.json") != std::string::npos);
    CHECK(r.err.find(message) != std::string::npos);
  }
  const Result missing = dir.run("inertia missing.json");
  CHECK(missing.code == 2);
  CHECK(missing.err.find("missing.json") != std::string::npos);
}

TEST_CASE("wedge: unknown verbs are named, help and --version answer", "[cli]") {
  TempDir dir;
  const Result unknown = dir.run("frobnicate");
  CHECK(unknown.code == 2);
  CHECK(unknown.out.empty());
  CHECK(unknown.err.find("unknown verb 'frobnicate'") != std::string::npos);
  const Result help = dir.run("help");
  CHECK(help.code == 0);
  CHECK(help.out.find("simulate") != std::string::npos);
  CHECK(help.out.find("render") != std::string::npos);
  const Result verb_help = dir.run("help simulate");
  CHECK(verb_help.code == 0);
  CHECK(verb_help.out.find("--steps") != std::string::npos);
  const Result version = dir.run("--version");
  CHECK(version.code == 0);
  CHECK(version.out.find("wedge 0.") == 0);
}

TEST_CASE("wedge view and wedge xr run the programs beside wedge, and name the one that is missing", "[cli]") {
  TempDir dir;
  // Through `wedge`: the verb's own program answers, with the verb's options.
  const Result view_help = dir.run("view --help");
  CHECK(view_help.code == 0);
  CHECK(view_help.out.find("Usage: wedge view") != std::string::npos);
  CHECK(view_help.out.find("--screenshot") != std::string::npos);
  const Result help_view = dir.run("help view");
  CHECK(help_view.code == 0);
  CHECK(help_view.out.find("--screenshot") != std::string::npos);
  // Its errors are the program's: one line naming the file, exit 2.
  const Result missing_scene = dir.run("view missing.json");
  CHECK(missing_scene.code == 2);
  CHECK(missing_scene.err == "wedge: missing.json: cannot open file (No such file or directory)\n");
  // A copy of `wedge` alone in a folder has no wedge-view beside it: it says which program to build.
  const fs::path lone = dir.path() / "lone";
  fs::create_directory(lone);
  fs::copy_file(cli_runner::kWedge, lone / "wedge");
  for (const std::string verb : {"view", "xr"}) {
    const Result r = dir.shell("lone/wedge " + verb + " scene.json");
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    const bool names_program = r.err.find("is the program wedge-" + verb + ", which is not built beside this one") !=
                                   std::string::npos &&
                               r.err.find("--target wedge-" + verb) != std::string::npos;
    const bool not_in_build = r.err.find("this build has no '" + verb + "' verb") != std::string::npos;
    CHECK((names_program || not_in_build));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("wedge: a directory given as a scene is named as one", "[cli]") {
  TempDir dir;
  fs::create_directory(dir.path() / "scenes.json");
  const Result r = dir.run("simulate scenes.json --steps 1");
  CHECK(r.code == 2);
  CHECK(r.err.find("scenes.json: is a folder, not a JSON file") != std::string::npos);
}

TEST_CASE("wedge simulate --out prints where the states went and the state hash", "[cli]") {
  TempDir dir;
  dir.write("projectile.json", kProjectile3);
  const Result r = dir.run("simulate projectile.json --steps 10 --every 5 --out states.jsonl --hash");
  REQUIRE(r.code == 0);
  const std::string file = read_file(dir.path() / "states.jsonl");
  const json last = json::parse(file.substr(file.rfind('\n', file.size() - 2) + 1));
  const std::string hash = last.at("state_hash");
  CHECK(r.out == "wrote 3 states (steps 0..10) to states.jsonl; state hash " + hash + "\n");
  // Without --out the states themselves are stdout: nothing else is printed there.
  const Result plain = dir.run("simulate projectile.json --steps 10 --every 5 --hash");
  CHECK(plain.out == file);
}

TEST_CASE("wedge simulate and render: Ctrl-C removes partial output and exits 130", "[cli]") {
  TempDir dir;
  // A long run: 200 balls falling onto a ground, 10^7 steps (hours), interrupted after half a second.
  std::string bodies = R"({"name": "ground", "static": true, "shape": {"type": "halfspace", "normal": [0, 1, 0], "offset": 0}})";
  for (int i = 0; i < 200; ++i)
    bodies += R"(, {"shape": {"type": "sphere", "radius": 0.2}, "position": [)" + std::to_string(i % 10) + ", " +
              std::to_string(1 + i / 10) + ", 0]}";
  dir.write("long.json", std::string(R"({"dim": 3, "gravity": [0, -9.81, 0], "bodies": [)") + bodies + "]}");
  for (const char* verb : {"simulate long.json --steps 10000000 --out out.jsonl",
                           "render long.json --steps 10000000 --every 1000 --out frames --size 64x64"}) {
    INFO(verb);
    const Result r = dir.shell(std::string("\"$WEDGE\" ") + verb + " & pid=$!; sleep 0.5; kill -INT $pid; wait $pid");
    CHECK(r.code == 130);
    CHECK(r.err.find("interrupted (SIGINT); partial output removed") != std::string::npos);
    CHECK(dir.listing() == std::vector<std::string>{"long.json"});  // no out.jsonl, no temporary, no frames
  }
}

TEST_CASE("wedge: usage errors exit with 2", "[cli]") {
  TempDir dir;
  dir.write("projectile.json", kProjectile3);
  for (const char* args : {"", "frobnicate", "simulate projectile.json --steps 1 --bogus", "simulate", "inertia",
                           "simulate a.json b.json --steps 1", "--bogus"}) {
    INFO(args);
    const Result r = dir.run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(!r.err.empty());
  }
}

TEST_CASE("wedge simulate: gyroscopic_method midpoint conserves a tumbling box's energy, euler dissipates it",
          "[cli]") {
  // A free box spun near its intermediate plane tumbles; exact motion conserves the kinetic energy.
  const std::string scene = R"({"dim": 4, "timestep": 0.008333, "gyroscopic_method": "METHOD",
    "bodies": [{"name": "cuboid", "shape": {"type": "box", "half_extents": [0.55, 0.15, 1.25, 0.35]},
                "angular_velocity": [3, 0.1, 0.2, 0.3, 0.1, 0.2]}]})";
  TempDir dir;
  auto energy_ratio = [&](const std::string& method) {
    std::string text = scene;
    text.replace(text.find("METHOD"), 6, method);
    dir.write("tumble.json", text);
    const Result r = dir.run("simulate tumble.json --steps 3600 --every 3600");
    REQUIRE(r.code == 0);
    const auto lines = r.lines();
    REQUIRE(lines.size() == 2);
    return lines[1]["energy"].get<double>() / lines[0]["energy"].get<double>();
  };
  // Midpoint: the body-frame rule conserves E up to Newton residuals and never gains; what is left is
  // round-off of the frame changes (~1e-16 a step, 3600 steps): |E/E0 - 1| < 1e-9.
  const double midpoint = energy_ratio("midpoint");
  CHECK(std::abs(midpoint - 1.0) < 1e-9);
  // Implicit Euler loses energy at a rate proportional to the sub-step: over 30 s of 8 sub-steps of
  // 1/960 s, more than 1% (2.7% measured; 8 times that at one sub-step of 1/120 s).
  CHECK(energy_ratio("euler") < 0.99);
}

// What each shipped scene must physically do over the steps its hash covers, read from the first and the
// last state `simulate` prints (energy, momenta, every body's centre, velocities and rotor). The hash only
// says the bits did not change; these say the bits are still right.
namespace {

double norm(const json& v) {
  double s = 0.0;
  for (const auto& x : v) s += x.get<double>() * x.get<double>();
  return std::sqrt(s);
}

json::const_iterator find_body(const json& state, const std::string& name) {
  const auto& bodies = state["bodies"];
  return std::find_if(bodies.begin(), bodies.end(), [&](const json& b) { return b["name"] == name; });
}

// No gravity, no contact: the implicit midpoint rule keeps the energy to round-off (1e-12 a step over 600
// steps: 1e-9) and linear momentum exactly up to round-off; the world angular momentum drifts at second
// order in the step (4.5e-5 relative over 5 s at 1/120 s for the 4D cuboid; tests/core/test_world.cpp
// measures the order), so 1e-3.
// A body's centre in a state line, and the distance between two points.
std::vector<double> center_of(const json& state, const std::string& name) {
  std::vector<double> v;
  for (const auto& x : (*find_body(state, name))["center"]) v.push_back(x.get<double>());
  return v;
}
double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(d);
}

void check_free_flight(const json& first, const json& last) {
  CHECK(close_rel(last["energy"].get<double>(), first["energy"].get<double>(), 1e-9));
  for (std::size_t i = 0; i < first["linear_momentum"].size(); ++i)
    CHECK(std::abs(last["linear_momentum"][i].get<double>() - first["linear_momentum"][i].get<double>()) <=
          1e-12 * (1.0 + norm(first["linear_momentum"])));
  json difference = json::array();
  for (std::size_t i = 0; i < first["angular_momentum"].size(); ++i)
    difference.push_back(last["angular_momentum"][i].get<double>() - first["angular_momentum"][i].get<double>());
  CHECK(norm(difference) <= 1e-3 * norm(first["angular_momentum"]));
}

// Gravity, no contact, no drag: each named body's velocity changes by exactly g T (a constant force;
// every integrator the step has adds g h per sub-step), to round-off over 4,800 sub-steps: 1e-9 relative.
void check_falling(const json& first, const json& last, const json& gravity, const std::vector<std::string>& names) {
  const double t = last["time"].get<double>() - first["time"].get<double>();
  for (const std::string& name : names) {
    INFO(name);
    const auto a = find_body(first, name), b = find_body(last, name);
    REQUIRE(a != first["bodies"].end());
    for (std::size_t i = 0; i < gravity.size(); ++i) {
      const double expected = (*a)["velocity"][i].get<double>() + gravity[i].get<double>() * t;
      CHECK(std::abs((*b)["velocity"][i].get<double>() - expected) <= 1e-9 * (1.0 + std::abs(expected)));
    }
  }
}

// Contacts only take energy out (restitution <= 1, friction, the soft step's damping): the energy at the
// end is no higher than at the start (1e-9 relative for round-off), and every body given has come to
// rest: under 1 cm/s and 0.05 rad/s, the sleeping thresholds' scale (resting bodies print exact zeros).
void check_settles(const json& first, const json& last, const std::vector<std::string>& names) {
  CHECK(last["energy"].get<double>() <= first["energy"].get<double>() * (1.0 + 1e-9));
  for (const std::string& name : names) {
    INFO(name);
    const auto b = find_body(last, name);
    REQUIRE(b != last["bodies"].end());
    CHECK(norm((*b)["velocity"]) < 1e-2);
    CHECK(norm((*b)["angular_velocity"]) < 5e-2);
  }
}

// A body that rests where it started (a stack that stands, a pyramid that holds) has its centre at the
// same height within `drop` metres: the soft contacts' compression under the load above.
void check_height_kept(const json& first, const json& last, const std::string& name, double drop) {
  INFO(name);
  const auto a = find_body(first, name), b = find_body(last, name);
  REQUIRE(a != first["bodies"].end());
  CHECK(std::abs((*b)["center"][1].get<double>() - (*a)["center"][1].get<double>()) < drop);
}

std::vector<std::string> names_with_prefix(const json& state, const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& b : state["bodies"]) {
    const std::string name = b["name"].get<std::string>();
    if (name.rfind(prefix, 0) == 0) names.push_back(name);
  }
  return names;
}

void check_shipped_scene_physics(const std::string& scene, const json& first, const json& last, const json& gravity) {
  if (scene == "free_5d.json" || scene == "free_6d.json" || scene == "regular_polytopes_4d.json" ||
      scene == "tumbling_4d_cuboid.json") {
    check_free_flight(first, last);
  } else if (scene == "spinning_2d.json") {
    check_falling(first, last, gravity, {"square", "triangle", "disk"});
  } else if (scene == "mesh_pentachoron.json") {
    check_falling(first, last, gravity, {"pentachoron"});
  } else if (scene == "projectile_3d.json") {
    check_falling(first, last, gravity, {"ball", "box"});
    // Linear drag only slows: the dragged ball ends slower than the free one thrown alike.
    CHECK(norm((*find_body(last, "ball_with_drag"))["velocity"]) < norm((*find_body(last, "ball"))["velocity"]));
  } else if (scene == "default.json") {
    // Thrown up, they land and come to rest on the ground, none below it (half heights 0.15 m and more).
    // The duocylinder lands on its round side and rolls to a stop: at 10 s it is still slowing (about
    // 1.5 cm/s, down from 5 m/s at landing); "wedge simulate: the default scene's bodies all fall asleep"
    // runs on until it sleeps.
    check_settles(first, last, {"tesseract", "hypercuboid"});
    CHECK(norm((*find_body(last, "duocylinder"))["velocity"]) < 5e-2);
    for (const char* name : {"tesseract", "hypercuboid", "duocylinder"})
      CHECK((*find_body(last, name))["center"][1].get<double>() > 0.14);
  } else if (scene == "fig1_stack_4d.json") {
    // The stack stands: at rest, each tesseract within 1 mm of its start height (0.4 mm measured).
    check_settles(first, last, {"tesseract0", "tesseract1", "tesseract2"});
    for (const char* name : {"tesseract0", "tesseract1", "tesseract2"}) check_height_kept(first, last, name, 1e-3);
  } else if (scene == "fig2_duocylinder_4d.json") {
    // Nothing sinks: every 0.3 m ball's centre stays at 0.3 m or above (1 mm of soft contact).
    CHECK(last["energy"].get<double>() < first["energy"].get<double>());
    for (const std::string& name : names_with_prefix(last, "ball_")) {
      INFO(name);
      CHECK((*find_body(last, name))["center"][1].get<double>() > 0.3 - 1e-3);
    }
  } else if (scene == "fig3_dominoes_4d.json") {
    // Every domino fell: turned by more than 45 degrees (rotor scalar cos(angle / 2) below cos(22.5 deg))
    // and at rest.
    const auto dominoes = names_with_prefix(last, "domino");
    CHECK(dominoes.size() == 12);
    check_settles(first, last, dominoes);
    for (const std::string& name : dominoes) {
      INFO(name);
      CHECK(std::abs((*find_body(last, name))["rotor"][0].get<double>()) < std::cos(22.5 * M_PI / 180.0));
    }
  } else if (scene == "fig4_spinning_4d.json") {
    // Thrown up spinning, it lands and rests on the ground (its thinnest half extent is 0.15 m).
    check_settles(first, last, {"hypercuboid"});
    CHECK((*find_body(last, "hypercuboid"))["center"][1].get<double>() > 0.14);
  } else if (scene == "toy_table_4d.json") {
    // Left alone, the toys rest on the table where they were put, within 5 mm (2 mm measured).
    const std::vector<std::string> toys = {"red", "blue", "cell24", "orange", "duocylinder"};
    check_settles(first, last, toys);
    for (const std::string& name : toys) check_height_kept(first, last, name, 5e-3);
  } else if (scene == "pyramid_2d.json" || scene == "pyramid_3d.json") {
    // The 20-row pyramid rests without collapsing: every box at rest and within 2 cm of its start height
    // (the soft contacts of 20 rows compress by 9 mm at the top).
    const auto boxes = names_with_prefix(last, "box_");
    CHECK(boxes.size() == 210);
    check_settles(first, last, boxes);
    for (const std::string& name : boxes) check_height_kept(first, last, name, 2e-2);
  } else if (scene == "pendulums_4d.json") {
    // Frictionless pendulums keep their energy (to 0.5% over 5 s; the soft step's joints lose a little
    // to their springs); the rod and the pins hold to 1 mm; each pendulum stays in its plane: the bob in
    // the plane of y and (x + w)/sqrt(2) through its pivot, the double pendulum in the x-y plane.
    CHECK(close_rel(last["energy"].get<double>(), first["energy"].get<double>(), 5e-3));
    const std::vector<double> bob = center_of(last, "bob"), upper = center_of(last, "upper"),
                              lower = center_of(last, "lower");
    CHECK(std::abs(distance(bob, {0.0, 2.0, -0.6, 0.0}) - 1.0) < 1e-3);
    CHECK(std::abs(bob[0] - bob[3]) < 1e-9);
    CHECK(bob[2] == -0.6);
    CHECK(distance(upper, {0.0, 1.9, 0.6, 0.0}) == Approx(0.3).margin(1e-3));
    CHECK(distance(upper, lower) < 0.6 + 1e-3);
    for (const auto& c : {upper, lower}) {
      CHECK(c[2] == 0.6);
      CHECK(c[3] == 0.0);
    }
  } else if (scene == "chain_4d.json") {
    // The pins hold: each link's centre within its half-length (8 cm) of its pin, each pair of
    // neighbours within a link's length, to 2 mm while the chain whips; the chain has fallen and
    // swung, and its collisions only took energy.
    const auto links = names_with_prefix(last, "link_");
    REQUIRE(links.size() == 12);
    std::vector<std::vector<double>> c;
    for (const std::string& name : links) c.push_back(center_of(last, name));
    CHECK(distance(c[0], {0.0, 1.975, 0.0, 0.0}) < 0.08 + 2e-3);
    for (std::size_t i = 1; i < c.size(); ++i) CHECK(distance(c[i - 1], c[i]) < 0.16 + 2e-3);
    CHECK(c.back()[1] < 1.5);
    CHECK(last["energy"].get<double>() < first["energy"].get<double>());
  } else if (scene == "door_4d.json") {
    // The door turns only in its hinge's plane, x-z: its rotor is cos(a/2) + sin(a/2) e02 but for the
    // rows' stretch under the door's weight (under 1 mrad off the plane); thrown open at 3 rad/s it is
    // held within 0.01 rad of its limits [-0.2, 1.6] and is open past 1 rad after 5 s; its centre stays
    // 0.25 m from the hinge line in the x-z plane (1 mm), at the hinge's height and w (2 mm); the cube
    // in its way was pushed along +z.
    const json& door = *std::find_if(last["bodies"].begin(), last["bodies"].end(),
                                     [](const json& b) { return b["name"] == "door"; });
    const std::vector<double> r = door["rotor"].get<std::vector<double>>();
    REQUIRE(r.size() == 8);
    for (const int k : {1, 3, 4, 5, 6, 7}) CHECK(std::abs(r[std::size_t(k)]) < 5e-4);
    const double angle = 2.0 * std::atan2(std::abs(r[2]), r[0]);
    CHECK(angle > 1.0);
    CHECK(angle < 1.61);
    const std::vector<double> c = center_of(last, "door");
    CHECK(std::hypot(c[0] - 0.02, c[2] + 0.2) == Approx(0.25).margin(1e-3));
    CHECK(std::abs(c[1] - 1.0) < 2e-3);
    CHECK(std::abs(c[3]) < 2e-3);
    CHECK(center_of(last, "cube")[2] > center_of(first, "cube")[2] + 0.05);
  } else if (scene == "cradle_4d.json") {
    // Five equal balls hang at rest 0.5 m under y = 1.5 but the first, raised to y0: the energy above
    // rest is m g (y0 - 1), a share (y0 - 1) / (4 + y0) of the total m g sum(y). After 5 s (seven
    // collisions) the swing has kept at least 85% of it (7.6% lost: the soft step's collisions are not
    // perfectly elastic), and gained none; every ball is on its rod (1 mm) and in the x-y plane.
    const auto balls = names_with_prefix(last, "ball_");
    REQUIRE(balls.size() == 5);
    const double y0 = center_of(first, "ball_0")[1], e0 = first["energy"].get<double>();
    const double swing0 = e0 * (y0 - 1.0) / (4.0 + y0), swing = last["energy"].get<double>() - (e0 - swing0);
    CHECK(swing > 0.85 * swing0);
    CHECK(swing < swing0 * (1.0 + 1e-3));
    for (std::size_t i = 0; i < balls.size(); ++i) {
      const std::vector<double> c = center_of(last, balls[i]);
      CHECK(distance(c, {(double(i) - 2.0) * 0.11, 1.5, 0.0, 0.0}) == Approx(0.5).margin(1e-3));
      CHECK(c[2] == 0.0);
      CHECK(c[3] == 0.0);
    }
  } else {
    FAIL("shipped scene " << scene << " has no physical check beside its hash: add one here");
  }
}

}  // namespace

// Determinism: every shipped scene has a recorded state hash (scenes/hashes.json, written by
// tools/update_scene_hashes.sh after an intentional physics change); the same binary inputs must give the
// same bits. Beside each hash, what the scene must physically do (check_shipped_scene_physics).
TEST_CASE("wedge simulate: shipped scenes reproduce their recorded state hashes", "[cli][determinism]") {
  const fs::path scenes = fs::path(WEDGE_SOURCE_DIR) / "scenes";
  const json recorded = json::parse(read_file(scenes / "hashes.json"));
  int count = 0;
  for (const auto& e : fs::directory_iterator(scenes)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".json" || name.rfind("inertia_", 0) == 0 || name == "hashes.json") continue;
    INFO(name);
    REQUIRE(recorded.contains(name));  // every scene has a hash
    const int steps = recorded[name]["steps"].get<int>();
    TempDir dir;
    const Result r = dir.run("simulate '" + e.path().string() + "' --steps " + std::to_string(steps) +
                             " --every " + std::to_string(steps) + " --hash");
    REQUIRE(r.code == 0);
    const auto lines = r.lines();
    REQUIRE(lines.size() == 3);  // step 0, the last step, the hash
    CHECK(lines.back()["state_hash"].get<std::string>() == recorded[name]["state_hash"].get<std::string>());
    const json scene = json::parse(read_file(e.path()));
    check_shipped_scene_physics(name, lines[0], lines[1], scene.value("gravity", json::array()));
    ++count;
  }
  CHECK(count == int(recorded.size()));
}

// The default scene run on to 15 s: the three bodies it throws up are asleep on the ground (a sleeping
// body prints exact zeros), the duocylinder, which rolls, included; the energy is below the start's.
TEST_CASE("wedge simulate: the default scene's bodies all fall asleep", "[cli]") {
  TempDir dir;
  const Result r = dir.run("simulate '" + (fs::path(WEDGE_SOURCE_DIR) / "scenes/default.json").string() +
                           "' --steps 900 --every 900");
  REQUIRE(r.code == 0);
  const auto lines = r.lines();
  REQUIRE(lines.size() == 2);
  CHECK(lines[1]["energy"].get<double>() < lines[0]["energy"].get<double>());
  for (const char* name : {"tesseract", "hypercuboid", "duocylinder"}) {
    INFO(name);
    const auto b = find_body(lines[1], name);
    REQUIRE(b != lines[1]["bodies"].end());
    CHECK(norm((*b)["velocity"]) == 0.0);
    CHECK(norm((*b)["angular_velocity"]) == 0.0);
    CHECK((*b)["center"][1].get<double>() > 0.14);
  }
}

// A key or a name with a line break in it (JSON allows "a\nb") is named with the break escaped: the
// refusal stays one line (found by fuzz_recording; tests/fuzz/corpus/README.md).
TEST_CASE("wedge: a key with a line break is named on one line", "[cli]") {
  TempDir dir;
  dir.write("s.json", R"({"dim": 3, "bodies": [], "x\ny": 1})");
  const Result scene = dir.run("simulate s.json --steps 1");
  CHECK(scene.code == 2);
  CHECK(scene.out.empty());
  CHECK(std::count(scene.err.begin(), scene.err.end(), '\n') == 1);
  CHECK(scene.err.find("s.json: x\\ny: unknown key") != std::string::npos);
  // A shipped recording's header, then a sample whose key holds an escaped line break.
  std::string header;
  std::getline(std::ifstream(fs::path(WEDGE_SOURCE_DIR) / "recordings/scripted/toy_table_grab.jsonl") >> std::ws, header);
  dir.write("r.jsonl", header + "\n{\"t\":0,\"type\":\"hand\",\"hand\":\"right\",\"position\":[0,0,0],\"ori\\ntation\":[1,0,0,0]}\n");
  dir.write("t.json", R"({"dim": 4, "bodies": []})");
  const Result replay = dir.run("replay t.json r.jsonl");
  INFO(replay.err);
  CHECK(replay.code == 2);
  CHECK(std::count(replay.err.begin(), replay.err.end(), '\n') == 1);
  CHECK(replay.err.find("r.jsonl:2: unknown key 'ori\\ntation'") != std::string::npos);
}
