// wedge slice SCENE.json [--w W] --obj FILE [--subdivisions S]
//
// Writes the 3D slice of a scene's bodies, as placed in the file (step 0), as a Wavefront OBJ: one
// object per body that the slice meets ("o NAME"), its vertices, one normal per triangle corner
// ("vn") and outward triangles ("f a//na b//nb c//nc"). The mesh of each body is closed and
// consistently oriented. The file appears atomically, only if everything succeeded.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "json_out.hpp"
#include "scene_slices.hpp"
#include "verbs.hpp"

namespace wedge::cli {

namespace {

// "x3 = 0.5" in 4D, "x4 = 1, x3 = 0" in 5D: the hyperplanes the offsets name.
template <int N>
std::string slice_description(const std::vector<double>& w) {
  std::string d;
  for (int i = 0; i < N - 3; ++i)
    d += (d.empty() ? "x" : ", x") + std::to_string(N - 1 - i) + " = " + format_number(i < int(w.size()) ? w[std::size_t(i)] : 0.0);
  return d.empty() ? "(the whole 3D scene)" : d;
}

std::string obj_numbers(const char* tag, const Eigen::Vector3d& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s %.9g %.9g %.9g", tag, v.x(), v.y(), v.z());
  return buf;
}

template <int N>
int slice(const Json& doc, const SliceOptions& o, const std::vector<double>& w, int subdivisions) {
  const std::string& file = o.scene;
  if constexpr (N < 3) {
    (void)doc, (void)w, (void)subdivisions;
    throw Failure(file + ": a 2D scene has no 3D slice (slice needs a 3D..6D scene)");
  } else {
    const Scene<N> scene = load_scene<N>(doc, file);
    const World<N> world = scene.make_world(file);
    slicing::WorldSlices<N> slices = scene_slices<N>(world, w, subdivisions, file);
    std::vector<slicing::DisplayMesh<3>> meshes;
    slices.slice(world, meshes);

    OutputSink out(o.obj);
    std::string where;
    for (double x : w) where += (where.empty() ? "" : ", ") + format_number(x);
    out.write_line("# wedge slice of " + file + " (" + std::to_string(N) + "D" +
                   (N > 3 ? ", offsets " + (where.empty() ? std::string("0") : where) : std::string()) + ")");
    std::size_t base_v = 1, base_n = 1;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
      const slicing::DisplayMesh<3>& m = meshes[k];
      if (m.empty()) continue;
      out.write_line("o " + scene.bodies[std::size_t(slices.entries()[k].body)].def.name);
      for (const Vec<3>& v : m.vertices) out.write_line(obj_numbers("v", v));
      for (const auto& corner : m.normals)
        for (const Vec<3>& n : corner) out.write_line(obj_numbers("vn", n));
      for (std::size_t c = 0; c < m.cells.size(); ++c) {
        char line[160];
        std::snprintf(line, sizeof line, "f %zu//%zu %zu//%zu %zu//%zu", base_v + std::size_t(m.cells[c][0]), base_n + 3 * c,
                      base_v + std::size_t(m.cells[c][1]), base_n + 3 * c + 1, base_v + std::size_t(m.cells[c][2]),
                      base_n + 3 * c + 2);
        out.write_line(line);
      }
      base_v += m.vertices.size();
      base_n += 3 * m.cells.size();
    }
    out.commit();
    if (base_v == 1)  // nothing met the slice: say so rather than leave an empty file unexplained
      std::fprintf(stderr, "wedge: warning: %s: the slice %s meets no body; %s holds no geometry\n", file.c_str(),
                   slice_description<N>(w).c_str(), o.obj.c_str());
    return kExitOk;
  }
}

}  // namespace

CLI::App* add_slice_verb(CLI::App& app, SliceOptions& o) {
  CLI::App* cmd = app.add_subcommand("slice", "Write the 3D slice of a scene's bodies (as placed in the file) as OBJ.");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--w", o.w,
                  "Where to slice (m): the hyperplane x3 = W in 4D; W1,W2 in 5D (x4 = W1, then x3 = W2), "
                  "W1,W2,W3 in 6D; default 0")
      ->type_name("W");
  cmd->add_option("--obj", o.obj, "Output file, Wavefront OBJ (required; written atomically)")->type_name("FILE");
  cmd->add_option("--subdivisions", o.subdivisions,
                  "Tessellation level of round shapes (1..64; default 16 in 3D, 8 in 4D, 4 in 5D, 2 in 6D)")
      ->type_name("S");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_slice(const SliceOptions& o) {
  if (o.obj.empty()) throw Failure(o.scene + ": --obj FILE is required");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  const std::vector<double> w = parse_slice_offsets(o.scene, o.w, n);
  const int subdivisions = parse_subdivisions(o.scene, o.subdivisions, n);
  return with_dim(n, [&](auto dim) { return slice<decltype(dim)::value>(doc, o, w, subdivisions); });
}

}  // namespace wedge::cli
