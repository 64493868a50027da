// Scene files (JSON) -> World<N>, keeping each body's shape, density and display colour for the tools.
// The schema is in docs/scene-format.md. Everything is checked while loading: unknown keys, types,
// sizes, ranges, finiteness, rotors, meshes (via the core's wedge::Error). Every problem comes out as a
// SceneError whose message starts with the file name and the JSON path: "scene.json: bodies[2].shape.
// half_extents: expected 4 numbers, got 3".
#pragma once

#include <array>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "wedge/scenes/error.hpp"
#include "wedge/scenes/json.hpp"
#include "wedge/body.hpp"
#include "wedge/error.hpp"
#include "wedge/mass.hpp"
#include "wedge/shape.hpp"
#include "wedge/world.hpp"

namespace wedge::scenes {

inline constexpr int kMinDim = 2, kMaxDim = 6;
inline constexpr double kDefaultTimestep = 1.0 / 120.0;
// The step sizes accepted (s), from a scene's "timestep" or --dt: below 1 us a run is all round-off; above
// 0.1 s contacts and turns are not resolved (a body falls 10 cm in one step) and results are nonsense.
inline constexpr double kMinTimestep = 1e-6, kMaxTimestep = 0.1;


template <int N>
struct SceneBody {
  BodyDef<N> def;  // mass, local_center and inertia filled from the shape and density
  Shape<N> shape;
  double density = 1.0;                     // kg/m^n; 0 for a halfspace (no mass properties)
  std::optional<MassProperties<N>> mass;    // absent for a halfspace
  Material material;
  std::optional<std::array<double, 3>> color;  // display colour (render, slice), RGB in [0, 1]
};

// The camera of `wedge render` ("view"); each part absent means "choose from the scene".
struct SceneView {
  std::optional<std::array<double, 3>> eye, target;  // m, in the 3D slice's coordinates
  std::optional<double> fov_degrees;                 // vertical field of view, in (0, 180)
};

// How hands and a phone reach the scene ("interaction", docs/input.md): where the tracking origin is
// in the world (its hidden coordinates are the slice the hands live in), the scale, and the gravity tilt.
template <int N>
struct SceneInteraction {
  Vec<N> origin = Vec<N>::Zero();  // m, world: the tracking origin; the default puts it at the origin (slice w = 0)
  double scale = 1.0;              // world metres per tracking metre, > 0
  double grab_radius = 0.05;       // m, >= 0: grab the nearest body this close when the hand is in none
  bool gravity_tilt_on = false;    // tilt gravity toward w from the start (4D and up)
  double gravity_tilt = 15.0;      // degrees, [0, 90]
};

// A joint ("joints", docs/scene-format.md): its definition, the bodies given as their indices in
// Scene::bodies (the BodyIds make_world gives them).
template <int N>
using SceneJoint =
    std::variant<PointJointDef<N>, DistanceJointDef<N>, RevoluteJointDef<N>, PrismaticJointDef<N>, WeldJointDef<N>>;

template <int N>
struct Scene {
  WorldSettings<N> settings;
  double timestep = kDefaultTimestep;  // s
  std::vector<SceneBody<N>> bodies;
  std::vector<SceneJoint<N>> joints;
  SceneView view;
  SceneInteraction<N> interaction;

  // A world holding every body, then every joint, in file order (throws SceneError naming the file and
  // the body or joint on error).
  World<N> make_world(const std::string& file) const;
};

// The "dim" of a document, checked to be an integer in 2..6; throws SceneError.
int read_dim(const Json& doc, const std::string& file);

// A shape object ({"type": ..}) at `node`; throws JsonError (or wedge::Error from the core, which the
// callers wrap with the path).
template <int N>
Shape<N> read_shape(const Node& node);

// Runs `what` and turns JsonError and wedge::Error into a SceneError prefixed with the file name (and,
// for wedge::Error, `path`).
template <class F>
decltype(auto) with_file_context(const std::string& file, const std::string& path, F&& what) {
  try {
    return std::forward<F>(what)();
  } catch (const JsonError& e) {
    throw SceneError(file + ": " + e.what());
  } catch (const Error& e) {
    throw SceneError(file + ": " + (path.empty() ? std::string() : path + ": ") + e.what());
  }
}

template <int N>
Scene<N> load_scene(const Json& doc, const std::string& file);

// Calls f(std::integral_constant<int, N>{}) for the runtime dimension n in 2..6.
template <class F>
decltype(auto) with_dim(int n, F&& f) {
  switch (n) {
    case 2: return f(std::integral_constant<int, 2>{});
    case 3: return f(std::integral_constant<int, 3>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 5: return f(std::integral_constant<int, 5>{});
    default: return f(std::integral_constant<int, 6>{});
  }
}

// Reads and loads a scene file whose "dim" must be N (tests, benchmarks); throws SceneError naming the file.
template <int N>
Scene<N> load_scene_file(const std::string& file) {
  const Json doc = read_json_file(file);
  const int n = read_dim(doc, file);
  if (n != N) throw SceneError(file + ": dim: expected " + std::to_string(N) + ", got " + std::to_string(n));
  return load_scene<N>(doc, file);
}

}  // namespace wedge::scenes
