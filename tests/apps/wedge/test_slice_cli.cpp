// `wedge slice`, run as a user would: the OBJ of a tesseract's w = 0 slice is read back here and checked
// against the cube (closed and outward through its directed edges, volume s^3 from the triangles,
// corner normals along the face axes); a slice that misses the body writes an empty OBJ; bad input
// exits 2 naming the file and leaves no file. Volume tolerance 1e-6: coordinates are written with 9
// significant digits.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace {

using namespace cli_runner;

struct Obj {
  std::vector<std::string> objects;
  std::vector<Eigen::Vector3d> v, vn;
  std::vector<std::array<int, 3>> f, fn;
};

Obj parse_obj(const std::string& text) {
  Obj o;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "o") {
      std::string name;
      ls >> name;
      o.objects.push_back(name);
    } else if (tag == "v" || tag == "vn") {
      Eigen::Vector3d p;
      ls >> p.x() >> p.y() >> p.z();
      (tag == "v" ? o.v : o.vn).push_back(p);
    } else if (tag == "f") {
      std::array<int, 3> a{}, b{};
      for (int q = 0; q < 3; ++q) {
        std::string corner;
        ls >> corner;
        const std::size_t slash = corner.find("//");
        a[std::size_t(q)] = std::stoi(corner.substr(0, slash)) - 1;
        b[std::size_t(q)] = std::stoi(corner.substr(slash + 2)) - 1;
      }
      o.f.push_back(a);
      o.fn.push_back(b);
    }
  }
  return o;
}

const char* kScene = R"({"dim": 4, "bodies": [
  {"name": "cube", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5, 0.5]}},
  {"name": "far", "shape": {"type": "ball", "radius": 0.3}, "position": [3, 0, 0, 2]}]})";

}  // namespace

TEST_CASE("wedge slice writes the slice as a closed outward OBJ mesh", "[cli][slice]") {
  TempDir dir;
  dir.write("s.json", kScene);
  const Result r = dir.run("slice s.json --w 0.1 --obj cube.obj");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const Obj o = parse_obj(read_file(dir.path() / "cube.obj"));
  CHECK(o.objects == std::vector<std::string>{"cube"});  // the ball at w = 2 is not cut
  REQUIRE(!o.f.empty());
  std::map<std::pair<int, int>, int> directed;
  double volume = 0.0;
  for (std::size_t t = 0; t < o.f.size(); ++t) {
    const auto& f = o.f[t];
    for (int q = 0; q < 3; ++q) ++directed[{f[std::size_t(q)], f[std::size_t((q + 1) % 3)]}];
    volume += o.v[std::size_t(f[0])].dot(o.v[std::size_t(f[1])].cross(o.v[std::size_t(f[2])])) / 6.0;
    for (int q = 0; q < 3; ++q) {
      const Eigen::Vector3d n = o.vn[std::size_t(o.fn[t][std::size_t(q)])];
      CHECK(n.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-8));
    }
  }
  for (const auto& [e, count] : directed) {
    CHECK(count == 1);
    CHECK(directed.count({e.second, e.first}) == 1);
  }
  CHECK(volume == Approx(1.0).epsilon(1e-6));
  // Not over-tessellated: the tesseract's 8 cells are cut as few tetrahedra (6 each), each giving at most
  // 2 triangles, so 96 at most; the slice was 4,352 triangles when boxes were subdivided like balls.
  CHECK(o.f.size() <= 96u);

  const Result none = dir.run("slice s.json --w 0.9 --obj none.obj");
  REQUIRE(none.code == 0);
  CHECK(parse_obj(read_file(dir.path() / "none.obj")).f.empty());
  // An empty slice is said, not left for the user to discover in an empty file.
  CHECK(none.err == "wedge: warning: s.json: the slice x3 = 0.9 meets no body; none.obj holds no geometry\n");
  CHECK(r.err.empty());
}

TEST_CASE("wedge slice: bad input exits 2 naming the file and writes nothing", "[cli][slice]") {
  TempDir dir;
  dir.write("s.json", kScene);
  dir.write("bad.json", R"({"dim": 4, "bodies": [{"shape": {"type": "box", "half_extents": [1, 1, 1]}}]})");
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"slice s.json", "s.json: --obj FILE is required"},
           {"slice s.json --obj o.obj --w 1,2", "s.json: --w takes at most 1"},
           {"slice bad.json --obj o.obj", "bad.json: bodies[0].shape.half_extents"}}) {
    const Result r = dir.run(args);
    INFO(args << "\n" << r.err);
    CHECK(r.code == 2);
    CHECK(r.err.rfind("wedge: " + message, 0) == 0);
    CHECK(!fs::exists(dir.path() / "o.obj"));
  }
}
