// The verbs of the `wedge` program. Each verb registers its subcommand and options with CLI11 and runs
// after parsing; it returns an exit code or throws Failure (exit code 2).
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace wedge::cli {

// wedge inertia FILE.json
struct InertiaOptions {
  std::string file;
};
CLI::App* add_inertia_verb(CLI::App& app, InertiaOptions& options);
int run_inertia(const InertiaOptions& options);

// wedge simulate SCENE.json --steps N [--dt H] [--every K] [--out FILE] [--hash]
// Numeric options are kept as text and checked by run_simulate, so that every message names the scene.
struct SimulateOptions {
  std::string scene;
  std::string steps, dt, every, workers;
  std::string out;
  bool hash = false;
};
CLI::App* add_simulate_verb(CLI::App& app, SimulateOptions& options);
int run_simulate(const SimulateOptions& options);

// wedge collide SCENE.json [--margin M] [--out FILE]
struct CollideOptions {
  std::string scene;
  std::string margin;
  std::string out;
};
CLI::App* add_collide_verb(CLI::App& app, CollideOptions& options);
int run_collide(const CollideOptions& options);

// wedge render SCENE.json --steps N [--every K] [--dt H] [--w W] --out DIR [--size WxH] [--subdivisions S]
//              [--sheet FILE] [--replay RECORDING...]
//   [--sheet FILE.png]
struct RenderOptions {
  std::string scene;
  std::string steps, dt, every, w, size, subdivisions;
  std::string out, sheet;
  std::vector<std::string> replay;  // recordings driving the scene through the input layer (as `replay`)
  bool no_joints = false;           // leave out the joint marks
};
CLI::App* add_render_verb(CLI::App& app, RenderOptions& options);
int run_render(const RenderOptions& options);

// wedge slice SCENE.json [--w W] --obj FILE [--subdivisions S]
struct SliceOptions {
  std::string scene;
  std::string w, subdivisions;
  std::string obj;
};
CLI::App* add_slice_verb(CLI::App& app, SliceOptions& options);
int run_slice(const SliceOptions& options);

// wedge import questset|coremotion SOURCE.csv --out RECORDING.jsonl
struct ImportOptions {
  std::string format;
  std::string source;
  std::string out;
};
CLI::App* add_import_verb(CLI::App& app, ImportOptions& options);
int run_import(const ImportOptions& options);

// wedge replay SCENE.json RECORDING... [--out FILE] [--every K] [--events FILE] [--hash] [--until T] [--dt H]
//                                     [--workers N]
struct ReplayOptions {
  std::string scene;
  std::vector<std::string> recordings;
  std::string out, events;
  std::string every, until, dt, workers;
  bool hash = false;
};
CLI::App* add_replay_verb(CLI::App& app, ReplayOptions& options);
int run_replay(const ReplayOptions& options);

// wedge view SCENE.json [--w W] [--size WxH] [--subdivisions S] [--play-subdivisions S]
//            [--replay RECORDING... | --record FILE] [--mouse FILE] [--events FILE] [--contacts] [--hash]
//            [--frames N --screenshot FILE.png]
inline constexpr const char* kViewSummary =
    "Open a window on the scene's 3D slice: play, pause, step, move the slice along w, orbit the camera.";
struct ViewOptions {
  std::string scene;
  std::string w, size, subdivisions, play_subdivisions, frames, screenshot, mouse, record, events;
  std::vector<std::string> replay;
  bool hash = false, contacts = false, no_joints = false;
};
CLI::App* add_view_verb(CLI::App& app, ViewOptions& options);
int run_view(const ViewOptions& options);

// wedge xr SCENE.json [--headless] [--record FILE] [--out FILE] [--every K] [--events FILE] [--hash]
//                     [--w W] [--subdivisions S] [--until T]  (built with the OpenXR SDK: WEDGE_HAVE_XR)
inline constexpr const char* kXrSummary =
    "Put the scene in a headset through OpenXR (the active runtime, or XR_RUNTIME_JSON): grab, turn and throw "
    "with the controllers, feel the hits. --headless runs input, physics and haptics without frames.";
struct XrOptions {
  std::string scene;
  std::string record, out, events, every, until, w, subdivisions;
  bool headless = false, hash = false;
};
CLI::App* add_xr_verb(CLI::App& app, XrOptions& options);
int run_xr(const XrOptions& options);

}  // namespace wedge::cli
