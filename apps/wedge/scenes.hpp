// The scene library (wedge/scenes) as the program uses it: the names it takes into the program's
// namespace, and its SceneError reported like the program's own Failure (cli_error.hpp).
#pragma once

#include "cli_error.hpp"
#include "wedge/scenes/error.hpp"
#include "wedge/scenes/json.hpp"
#include "wedge/scenes/scene.hpp"

namespace wedge::cli {
using scenes::format_number;
using scenes::Json;
using scenes::JsonError;
using scenes::kMaxTimestep;
using scenes::kMinTimestep;
using scenes::load_scene;
using scenes::Node;
using scenes::ObjectReader;
using scenes::read_dim;
using scenes::read_json_file;
using scenes::read_shape;
using scenes::Scene;
using scenes::SceneBody;
using scenes::SceneError;
using scenes::with_dim;
using scenes::with_file_context;
}  // namespace wedge::cli
