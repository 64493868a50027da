// The scene library (wedge/scenes) as the program uses it: its names in the program's namespace, and its
// SceneError reported like the program's own Failure (cli_error.hpp).
#pragma once

#include "cli_error.hpp"
#include "wedge/scenes/json.hpp"
#include "wedge/scenes/scene.hpp"

namespace wedge::cli {
using namespace wedge::scenes;
}  // namespace wedge::cli
