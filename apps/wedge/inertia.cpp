// wedge inertia FILE.json
//
// Reads {"dim": n, "shape": {..}, "density": d} (or "mass": m instead of the density) and prints the
// shape's mass properties as one JSON object: volume, mass, centre of mass, the k x k bivector inertia
// tensor about the centre in the shape's axes, and the principal frame (axes as the columns of an n x n
// matrix, the inertia diagonal in it). Formats: docs/scene-format.md.
#include <CLI/CLI.hpp>

#include "json_out.hpp"
#include "scenes.hpp"
#include "verbs.hpp"
#include "wedge/error.hpp"

namespace wedge::cli {

namespace {

template <int N>
int inertia(const Json& doc, const std::string& file) {
  const OutJson result = with_file_context(file, "", [&] {
    ObjectReader obj(Node(doc, ""));
    obj.required("dim");  // read_dim checked it
    if (auto n = obj.optional("description")) n->string();
    const Node shape_node = obj.required("shape");
    const Shape<N> shape = read_shape<N>(shape_node);
    if (!shape.bounded()) shape_node.fail("a halfspace is infinite: it has no mass properties");
    const std::optional<Node> density_node = obj.optional("density");
    const std::optional<Node> mass_node = obj.optional("mass");
    obj.finish();
    if (density_node && mass_node) mass_node->fail("give either \"density\" or \"mass\", not both");
    double density = 1.0;
    if (density_node) {
      density = density_node->number();
      if (!(density > 0.0)) density_node->fail("must be > 0 (got " + density_node->json().dump() + ")");
    }
    std::optional<double> mass;
    if (mass_node) {
      mass = mass_node->number();
      if (!(*mass > 0.0)) mass_node->fail("must be > 0 (got " + mass_node->json().dump() + ")");
    }

    MassProperties<N> mp;
    PrincipalFrame<N> frame;
    try {
      mp = mass_properties<N>(shape, density);
      if (mass) mp = with_mass<N>(mp, *mass);
      frame = principal_frame<N>(mp);
    } catch (const Error& e) {
      throw JsonError(shape_node.path(), e.what());
    }

    OutJson out;
    out["dim"] = N;
    out["volume"] = mp.volume;
    out["mass"] = mp.mass;
    out["density"] = mp.mass / mp.volume;
    out["center"] = to_json(mp.center);
    out["covariance"] = to_json_rows(mp.covariance);
    out["inertia"] = to_json_rows(mp.inertia);
    out["principal_axes"] = to_json_rows(frame.axes);  // columns are the axes
    out["principal_covariance"] = to_json(frame.covariance);
    out["principal_inertia"] = to_json_rows(frame.inertia);
    if (!all_finite(out))
      shape_node.fail("mass properties are not finite; is the shape degenerate or the density extreme?");
    return out;
  });
  OutputSink sink("");
  sink.write_line(result.dump());
  sink.commit();
  return kExitOk;
}

}  // namespace

CLI::App* add_inertia_verb(CLI::App& app, InertiaOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "inertia",
      "Print the mass properties of a shape as JSON: volume, mass, centre of mass, bivector inertia "
      "tensor and principal frame.");
  cmd->add_option("file", o.file, "Input file: {\"dim\": n, \"shape\": {..}, \"density\": d} (docs/scene-format.md)")
      ->required()
      ->type_name("FILE.json");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_inertia(const InertiaOptions& o) {
  const Json doc = read_json_file(o.file);
  const int n = read_dim(doc, o.file);
  return with_dim(n, [&](auto dim) { return inertia<decltype(dim)::value>(doc, o.file); });
}

}  // namespace wedge::cli
