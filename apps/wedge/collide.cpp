// wedge collide SCENE.json [--margin M] [--out FILE]
//
// Places every body of a scene where the file puts it and runs collision detection once: the broad phase
// (an AABB tree) finds the pairs whose bounding boxes overlap, the narrow phase computes each pair's
// depth, normal and contact points. Half-spaces are unbounded: one is paired with every body whose box
// reaches below its plane; two half-spaces are never paired. Output (JSON):
//   {"pairs": [{"a": NAME, "b": NAME, "intersecting": BOOL, "depth": D, "normal": [..],
//               "contacts": [{"point": [..], "depth": D, "id": "<16 hex digits>"}]}]}
// depth >= 0 is the penetration along the normal (from a to b); for a pair apart, -distance.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "json_out.hpp"
#include "scenes.hpp"
#include "verbs.hpp"
#include "wedge/collision/aabb.hpp"
#include "wedge/collision/detail/broadphase.hpp"
#include "wedge/collision/narrow_phase.hpp"
#include "wedge/fp_env.hpp"
#include "wedge/ga/products.hpp"

namespace wedge::cli {
namespace {

template <int N>
OutJson pair_json(const std::string& a, const std::string& b, const Manifold<N>& m) {
  OutJson p;
  p["a"] = a;
  p["b"] = b;
  p["intersecting"] = m.intersecting;
  p["depth"] = m.depth;
  p["normal"] = to_json(m.normal);
  OutJson contacts = OutJson::array();
  for (int i = 0; i < m.count; ++i) {
    OutJson c;
    c["point"] = to_json(m.points[i].point);
    c["depth"] = m.points[i].depth;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016" PRIx64, m.points[i].id);
    c["id"] = hex;
    contacts.push_back(std::move(c));
  }
  p["contacts"] = std::move(contacts);
  return p;
}

template <int N>
int collide_scene(const Json& doc, const CollideOptions& options, double margin) {
  const std::string& file = options.scene;
  const Scene<N> scene = load_scene<N>(doc, file);
  const int count = int(scene.bodies.size());
  std::vector<Transform<N>> where(count);
  for (int i = 0; i < count; ++i) where[i] = {scene.bodies[i].def.position, to_matrix(scene.bodies[i].def.rotor)};

  // Bounded bodies go through the broad phase (tight boxes: no fattening for a one-off query).
  BroadPhaseSettings bp_settings;
  bp_settings.margin = 0.0;
  BroadPhase<N> broad(bp_settings);
  std::vector<Aabb<N>> boxes(count);
  for (int i = 0; i < count; ++i) {
    const Shape<N>& s = scene.bodies[i].shape;
    if (!s.bounded()) continue;
    boxes[i] = world_aabb(s, where[i].position, where[i].rotation);
    broad.create_proxy(boxes[i], std::uint32_t(i));
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  broad.update_pairs(pairs);
  // Half-spaces against every bounded body whose box reaches below the plane.
  for (int h = 0; h < count; ++h) {
    const Shape<N>& s = scene.bodies[h].shape;
    if (s.bounded()) continue;
    const auto& hs = s.template as<shapes::Halfspace<N>>();
    const Vec<N> n = where[h].rotation * hs.normal;
    const double offset = hs.offset + n.dot(where[h].position);
    for (int i = 0; i < count; ++i) {
      if (!scene.bodies[i].shape.bounded()) continue;
      double lowest = 0.0;  // min of n . x over the box's corners
      for (int k = 0; k < N; ++k) lowest += n[k] * (n[k] >= 0.0 ? boxes[i].lo[k] : boxes[i].hi[k]);
      if (lowest <= offset) pairs.emplace_back(std::uint32_t(std::min(h, i)), std::uint32_t(std::max(h, i)));
    }
  }
  std::sort(pairs.begin(), pairs.end());

  CollisionSettings settings;
  settings.contact_margin = margin;
  OutJson list = OutJson::array();
  for (const auto& [i, j] : pairs) {
    const Manifold<N> m = collide(scene.bodies[i].shape, where[i], scene.bodies[j].shape, where[j], settings);
    list.push_back(pair_json(scene.bodies[i].def.name, scene.bodies[j].def.name, m));
  }
  OutJson result;
  result["pairs"] = std::move(list);
  if (const std::string bad = first_non_finite(result); !bad.empty())  // never bad input: finite shapes give finite results
    throw InternalError(file + ": collision detection produced a non-finite value at " + bad);
  OutputSink out(options.out);
  out.write_line(result.dump());
  out.commit();
  return kExitOk;
}

}  // namespace

CLI::App* add_collide_verb(CLI::App& app, CollideOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "collide", "Run collision detection once on a scene as placed in the file; print the pairs whose bounding "
                 "boxes overlap with their depth, normal and contact points (JSON).");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--margin", o.margin,
                  "Also report contact points with a gap up to M metres (negative depth; default 0)")
      ->type_name("M");
  cmd->add_option("--out,-o", o.out, "Write to FILE (atomically) instead of stdout")->type_name("FILE");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_collide(const CollideOptions& o) {
  double margin = 0.0;
  if (!o.margin.empty()) {
    const ExpectedFpExceptions quiet;  // "1e999" overflows: refused below
    char* end = nullptr;
    margin = std::strtod(o.margin.c_str(), &end);
    if (end != o.margin.c_str() + o.margin.size() || !std::isfinite(margin) || margin < 0.0)
      throw Failure(o.scene + ": --margin must be a finite number >= 0 (got '" + o.margin + "')");
  }
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  return with_dim(n, [&](auto dim) { return collide_scene<decltype(dim)::value>(doc, o, margin); });
}

}  // namespace wedge::cli
