// wedge render SCENE.json --steps N [--every K] [--dt H] [--w W] --out DIR [--size WxH] [--subdivisions S]
//              [--sheet FILE.png] [--replay RECORDING...] [--no-joints]
//
// Simulates a scene and draws the 3D slice of every K-th state (step 0 included) offscreen, through
// OSMesa, into DIR/frame_00000.png, frame_00001.png, ... and, with --sheet, one contact sheet: up to 12
// of those frames picked evenly over the run (first and last included), downscaled into a grid 4 wide,
// each labelled with its time. The joints are marked over the bodies as `wedge view` marks them (anchors,
// rods, a revolute joint's plane and turn, a prismatic joint's axis). Everything is checked and the whole run is simulated before the first
// frame is written. Every PNG is written atomically (a .part file renamed into place); if anything fails
// or the run is interrupted (Ctrl-C) while writing, the frames and sheet written so far are removed, and
// so is the output folder if this run made it and it is left empty.
// The camera looks from an elevated three-quarter view with the scene's "down" (gravity, projected into
// the slice) pointing down the screen, at a distance that just fits, with a margin, every body's slice in
// every drawn frame and its shadow on the ground, unless the scene's "view" says otherwise
// (docs/scene-format.md).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "fp_traps.hpp"
#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scene_frame.hpp"
#include "scene_slices.hpp"
#include "verbs.hpp"
#include "view_overlays.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/png.hpp"
#include "wedge/render/renderer.hpp"

namespace wedge::cli {

namespace {

namespace fs = std::filesystem;

// A progress bar on stderr, only when stderr is a terminal.
class Progress {
 public:
  Progress(const char* what, std::int64_t total) : what_(what), total_(total), on_(::isatty(2) == 1) {}
  void update(std::int64_t done) {
    if (!on_) return;
    const int width = 30, filled = total_ > 0 ? int(width * done / total_) : width;
    std::fprintf(stderr, "\r%s [%s%s] %lld/%lld", what_, std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(width - filled), '.').c_str(), (long long)done, (long long)total_);
    std::fflush(stderr);
  }
  void finish() {
    if (on_) std::fprintf(stderr, "\n");
  }

 private:
  const char* what_;
  std::int64_t total_;
  bool on_;
};

template <int N>
struct Pose {
  Vec<N> center;
  Rotor<N> rotor;
};

// A mark drawn over a frame of a replay (view_overlays.hpp): a hand, or where a held body hit.
struct Mark {
  Eigen::Vector3d at;  // m, slice coordinates
  double half = 0.0;   // m: the cube's half size
  render::Color color;
};

// The marks of a replay's frame: each tracked hand (green while it holds a body, yellow if a haptic pulse
// went to it since the last frame drawn), and the points where those pulses' bodies met.
template <int N>
std::vector<Mark> replay_marks(const input::Interaction<N>& hands, const slicing::WorldSlices<N>& slices,
                               const std::vector<input::HapticPulse<N>>& pulses) {
  std::vector<Mark> marks;
  for (int k = 0; k < input::kHandCount; ++k) {
    if (!hands.tracked(k)) continue;
    const bool flash = std::any_of(pulses.begin(), pulses.end(), [k](const auto& p) { return p.hand == k; });
    const bool holding = hands.held(k).has_value();
    marks.push_back({slices.to_slice_point(hands.hand_point(k)), flash || holding ? 0.05 : 0.04,
                     hand_color(k, holding, flash)});
  }
  for (const input::HapticPulse<N>& p : pulses) marks.push_back({slices.to_slice_point(p.point), 0.05, kFlashColor});
  return marks;
}

// The sheet's tiles: at most this many frames, this many to a row, at most this wide (px).
constexpr int kSheetTiles = 12, kSheetColumns = 4, kSheetTileWidth = 400;

// A path made absolute and normal, without a trailing separator (for comparing folders).
fs::path normal_path(const fs::path& p) {
  fs::path a = fs::absolute(p).lexically_normal();
  if (!a.has_filename() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}


template <int N>
int render(const Json& doc, const RenderOptions& o, const StepOptions& run, const std::vector<double>& w,
           int subdivisions, const Size& size, const std::string& sheet_path) {
  const std::string& file = o.scene;
  if constexpr (N < 3) {
    (void)doc, (void)run, (void)w, (void)subdivisions, (void)size, (void)sheet_path;
    throw Failure(file + ": a 2D scene cannot be rendered (render shows 3D slices of 3D..6D scenes)");
  } else {
    const Scene<N> scene = load_scene<N>(doc, file);
    const double h = run.dt ? *run.dt : scene.timestep;
    World<N> world = scene.make_world(file);
    slicing::WorldSlices<N> slices = scene_slices<N>(world, w, subdivisions, file);
    std::optional<ReplayInput<N>> replay;  // --replay: recordings drive the world through the input layer
    if (!o.replay.empty()) replay.emplace(scene, world, o.replay, file, h);

    // Simulate first: the states of the frames to draw, and the corners of the box around every body's
    // slice in every one of them: what the camera must show.
    std::vector<std::vector<Pose<N>>> frames;
    std::vector<std::vector<Mark>> frame_marks;      // --replay: the hands, per frame
    std::vector<input::HapticPulse<N>> recent_pulses;  // --replay: since the last frame recorded
    std::vector<Eigen::Vector3d> points;
    std::vector<slicing::DisplayMesh<3>> meshes;
    std::vector<bool> seen;  // per sliced body: met the slice in some drawn frame
    auto record = [&] {
      std::vector<Pose<N>> poses;
      for (int i = 0; i < world.body_count(); ++i) {
        const Body<N>& b = world.body(BodyId{std::uint32_t(i)});
        poses.push_back({b.center, b.rotor});
      }
      frames.push_back(std::move(poses));
      frame_marks.push_back(replay ? replay_marks(replay->interaction(), slices, recent_pulses) : std::vector<Mark>{});
      recent_pulses.clear();
      slices.slice(world, meshes);
      seen.resize(meshes.size(), false);
      for (std::size_t k = 0; k < meshes.size(); ++k) seen[k] = seen[k] || !meshes[k].empty();
      add_box_corners(meshes, points);
      const JointMarks joints = joint_marks(world, slices, meets_slice(meshes));  // (a pendulum's pivot too)
      points.insert(points.end(), joints.anchors.begin(), joints.anchors.end());
    };
    Progress sim_progress("simulate", run.steps);
    record();
    for (std::int64_t s = 1; s <= run.steps; ++s) {
      if (replay) {
        replay->step();
        const auto& pulses = replay->session().pulses();
        recent_pulses.insert(recent_pulses.end(), pulses.begin(), pulses.end());
        replay->session().clear_output();
      } else {
        checked_step(world, h, file);  // checks for Ctrl-C first
      }
      if (s % run.every == 0) record();
      if (s % 64 == 0) sim_progress.update(s);
    }
    sim_progress.update(run.steps);
    sim_progress.finish();
    // Bodies the pictures never show (out of the slice all along) are named rather than silently missing.
    std::string unseen;
    int unseen_count = 0;
    for (std::size_t k = 0; k < seen.size(); ++k)
      if (!seen[k]) {
        unseen += (unseen.empty() ? "'" : ", '") + scene.bodies[std::size_t(slices.entries()[k].body)].def.name + "'";
        ++unseen_count;
      }
    if (unseen_count > 0)
      std::cerr << "wedge: warning: " << file << ": " << unseen << (unseen_count == 1 ? " never meets" : " never meet")
                << " the drawn slice in any frame (move the slice with --w)\n";

    render::FrameDesc frame = fitted_frame(scene, world, slices, points, size.width, size.height);
    const double mark = mark_size(slices);

    // The sheet's tiles: frames spread evenly over the run, the first and the last included.
    const int frame_count = int(frames.size());
    const int tiles = std::min(frame_count, kSheetTiles);
    auto tile_frame = [&](int i) {
      if (tiles == 1) return 0;
      return int((2 * std::int64_t(i) * (frame_count - 1) + tiles - 1) / (2 * std::int64_t(tiles - 1)));
    };
    std::optional<render::ContactSheet> sheet;
    if (!sheet_path.empty()) {
      const int tw = std::min(size.width, kSheetTileWidth);
      const int th = std::max(1, int(std::lround(double(size.height) * tw / size.width)));
      sheet.emplace(tiles, kSheetColumns, tw, th);
    }

    // Draw and write. On any failure or interruption: remove what this run wrote, then rethrow.
    const MesaArithmetic mesa;  // (the steps above ran with the traps WEDGE_FP_TRAPS asks for)
    render::OffscreenContext context(size.width, size.height);
    render::Renderer renderer;
    const fs::path dir(o.out);
    std::vector<fs::path> written, created;  // created: folders this run made, deepest first
    bool sheet_written = false;
    Progress progress("render", std::int64_t(frames.size()));
    try {
      for (fs::path p = normal_path(dir); !p.empty() && !fs::exists(p); p = p.parent_path()) {
        created.push_back(p);
        if (p == p.parent_path()) break;
      }
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec || !fs::is_directory(dir))
        throw Failure(o.out + ": cannot create the output folder (" + ec.message() + ")");
      int next_tile = 0;
      for (std::size_t f = 0; f < frames.size(); ++f) {
        throw_if_interrupted();
        for (int i = 0; i < world.body_count(); ++i) {
          Body<N>& b = world.body(BodyId{std::uint32_t(i)});
          b.center = frames[f][std::size_t(i)].center;
          b.rotor = frames[f][std::size_t(i)].rotor;
        }
        slices.slice(world, meshes);
        frame.meshes.clear();
        for (std::size_t k = 0; k < meshes.size(); ++k) {
          const SceneBody<N>& sb = scene.bodies[std::size_t(slices.entries()[k].body)];
          render::Color color = render::palette_color(int(k));
          if (sb.color) color = {float((*sb.color)[0]), float((*sb.color)[1]), float((*sb.color)[2])};
          frame.meshes.push_back({&meshes[k], color});
        }
        std::vector<slicing::DisplayMesh<3>> marks;  // the joints (as the viewer draws them), then the hands
        std::vector<render::Color> colors;
        if (!o.no_joints) add_joint_meshes(joint_marks(world, slices, meets_slice(meshes)), mark, marks, colors);
        for (const Mark& m : frame_marks[f]) {
          marks.push_back(marker_cube(m.at, m.half));
          colors.push_back(m.color);
        }
        for (std::size_t k = 0; k < marks.size(); ++k) frame.meshes.push_back({&marks[k], colors[k], true});
        renderer.draw(frame, size.width, size.height);
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05zu.png", f);
        const std::vector<std::uint8_t> pixels = context.read_rgba();
        render::write_png((dir / name).string(), pixels, size.width, size.height);  // all or nothing
        written.push_back(dir / name);
        if (sheet && next_tile < tiles && tile_frame(next_tile) == int(f)) {
          char label[32];
          std::snprintf(label, sizeof label, "t=%.2f s", double(f) * double(run.every) * h);
          sheet->place(next_tile++, pixels, size.width, size.height, label);
        }
        progress.update(std::int64_t(f + 1));
      }
      if (sheet) {
        throw_if_interrupted();
        render::write_png(sheet_path, sheet->rgba(), sheet->width(), sheet->height());
        sheet_written = true;
      }
    } catch (...) {
      progress.finish();
      std::error_code ec;
      for (const fs::path& p : written) fs::remove(p, ec);
      if (sheet_written) fs::remove(sheet_path, ec);
      for (const fs::path& p : created) fs::remove(p, ec);  // only if empty
      try {
        throw;
      } catch (const Error& e) {
        throw Failure(e.what());
      }
    }
    progress.finish();
    std::cout << "wrote " << frames.size() << " frame" << (frames.size() == 1 ? "" : "s") << " (" << size.width << "x"
              << size.height << ") to " << o.out;
    if (sheet)
      std::cout << " and a sheet of " << tiles << " (" << sheet->width() << "x" << sheet->height() << ") to "
                << sheet_path;
    std::cout << "\n";
    return kExitOk;
  }
}

}  // namespace

CLI::App* add_render_verb(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "render", "Simulate a scene and write PNG pictures of its 3D slice: step 0 and every K-th step up to N.");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--steps,-n", o.steps, "Number of steps to run (required, >= 0)")->type_name("N");
  cmd->add_option("--every,-k", o.every, "Draw every K-th step (>= 1; default 1); step 0 is always drawn")->type_name("K");
  cmd->add_option("--dt", o.dt, "Step size in seconds (> 0; default: the scene's \"timestep\", else 1/120)")->type_name("H");
  cmd->add_option("--w", o.w,
                  "Where to slice (m): the hyperplane x3 = W in 4D; W1,W2 in 5D (x4 = W1, then x3 = W2), "
                  "W1,W2,W3 in 6D; default 0. Not for 3D scenes, which are drawn as they are")
      ->type_name("W");
  cmd->add_option("--out,-o", o.out, "Folder for frame_00000.png, frame_00001.png, .. (created if needed)")
      ->type_name("DIR");
  cmd->add_option("--size", o.size, "Picture size in pixels (default 1280x720)")->type_name("WxH");
  cmd->add_option("--sheet", o.sheet,
                  "Also write a contact sheet: up to 12 frames picked evenly over the run (first and last "
                  "included), downscaled into one PNG grid 4 wide, each labelled with its time")
      ->type_name("FILE.png");
  cmd->add_option("--replay", o.replay,
                  "Recordings (docs/recording-format.md) that drive the scene through the input layer while it "
                  "is drawn, as `wedge replay` does; the hands are marked (left cyan, right magenta, green while "
                  "holding, yellow with a haptic pulse, and the hit's point)")
      ->type_name("RECORDING...")
      ->expected(1, -1);
  cmd->add_flag("--no-joints", o.no_joints,
                "Leave out the joint marks (drawn otherwise: anchors, rods, a revolute joint's plane and turn, a "
                "prismatic joint's axis)");
  cmd->add_option("--subdivisions", o.subdivisions,
                  "Tessellation level of round shapes (1..64; default 16 in 3D, 8 in 4D, 4 in 5D, 2 in 6D)")
      ->type_name("S");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_render(const RenderOptions& o) {
  const StepOptions run = parse_step_options(o.scene, o.steps, o.dt, o.every);
  const Size size = parse_size(o.scene, o.size, 16, 16);
  if (o.out.empty()) throw Failure(o.scene + ": --out DIR is required");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  const std::vector<double> w = parse_slice_offsets(o.scene, o.w, n);
  const int subdivisions = parse_subdivisions(o.scene, o.subdivisions, n);
  const std::string& sheet = o.sheet;
  if (!sheet.empty()) {
    // Its folder must exist, or be the one --out creates; checked before the run, like everything.
    const fs::path parent = fs::path(sheet).has_parent_path() ? fs::path(sheet).parent_path() : fs::path(".");
    if (fs::is_directory(sheet) || !fs::path(sheet).has_filename())
      throw Failure(o.scene + ": --sheet must name a file (got '" + sheet + "')");
    if (!fs::is_directory(parent) && normal_path(parent) != normal_path(o.out))
      throw Failure(o.scene + ": --sheet: the folder '" + parent.string() + "' does not exist");
  }
  return with_dim(n, [&](auto dim) {
    return render<decltype(dim)::value>(doc, o, run, w, subdivisions, size, sheet);
  });
}

}  // namespace wedge::cli
