// wedge render SCENE.json --steps N [--every K] [--dt H] [--w W] --out DIR [--size WxH] [--subdivisions S]
//              [--sheet FILE.png] [--replay RECORDING...]
//
// Simulates a scene and draws the 3D slice of every K-th state (step 0 included) offscreen, through
// OSMesa, into DIR/frame_00000.png, frame_00001.png, ... and, with --sheet, one contact sheet: up to 12
// of those frames picked evenly over the run (first and last included), downscaled into a grid 4 wide,
// each labelled with its time. Everything is checked and the whole run is simulated before the first
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

#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scene_slices.hpp"
#include "verbs.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/png.hpp"
#include "wedge/render/renderer.hpp"

namespace wedge::cli {

namespace {

namespace fs = std::filesystem;

struct Size {
  int width = 1280, height = 720;
};

Size parse_size(const std::string& scene, const std::string& text) {
  Size s;
  if (text.empty()) return s;
  const std::size_t x = text.find('x');
  std::int64_t w = 0, h = 0;
  if (x == std::string::npos || !parse_int64(text.substr(0, x), w) || !parse_int64(text.substr(x + 1), h) || w < 16 ||
      h < 16 || w > 8192 || h > 8192)
    throw Failure(scene + ": --size must be WIDTHxHEIGHT with each in 16..8192 pixels (got '" + text + "')");
  s.width = int(w);
  s.height = int(h);
  return s;
}

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

// The sheet's tiles: at most this many frames, this many to a row, at most this wide (px).
constexpr int kSheetTiles = 12, kSheetColumns = 4, kSheetTileWidth = 400;

// A path made absolute and normal, without a trailing separator (for comparing folders).
fs::path normal_path(const fs::path& p) {
  fs::path a = fs::absolute(p).lexically_normal();
  if (!a.has_filename() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}

// The camera's view direction (from the target toward the eye) and screen axes for a given up.
struct ViewAxes {
  Eigen::Vector3d dir, right, screen_up;
};

ViewAxes default_view_axes(const Eigen::Vector3d& up) {
  // Toward the viewer: the slice axis least aligned with up (z when up is y), then right = up x it.
  Eigen::Index axis = 0;
  (Eigen::Vector3d(0.5, 0.5, 0.0) + up.cwiseAbs()).minCoeff(&axis);  // prefers z, then x
  Eigen::Vector3d toward = Eigen::Vector3d::Unit(axis) - up * up(axis);
  toward.normalize();
  const Eigen::Vector3d right = up.cross(toward);
  // About 30 degrees above the ground and 28 to the side: the ground and the shadows on it show well.
  const Eigen::Vector3d dir = (0.85 * toward + 0.55 * up + 0.45 * right).normalized();
  const Eigen::Vector3d f = -dir;  // as Camera::view() builds its axes
  const Eigen::Vector3d s = f.cross(up).normalized();
  return {dir, s, s.cross(f)};
}

// The distance from `target` along ax.dir at which every point lies within `fill` of the picture's half
// width and half height (tan_x, tan_y: tangents of the half fields of view), and at least `min_depth`
// in front of the eye.
double fit_distance(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& target, const ViewAxes& ax,
                    double tan_x, double tan_y, double fill, double min_depth) {
  double d = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = p - target;
    const double need = std::max({std::abs(ax.right.dot(q)) / (fill * tan_x),
                                  std::abs(ax.screen_up.dot(q)) / (fill * tan_y), min_depth});
    d = std::max(d, ax.dir.dot(q) + need);
  }
  return d;
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
    if (!o.replay.empty()) replay.emplace(scene, world, o.replay, file);

    // Simulate first: the states of the frames to draw, and the corners of the box around every body's
    // slice in every one of them: what the camera must show.
    std::vector<std::vector<Pose<N>>> frames;
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
      slices.slice(world, meshes);
      seen.resize(meshes.size(), false);
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        const slicing::DisplayMesh<3>& m = meshes[k];
        if (m.empty()) continue;
        seen[k] = true;
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
        for (const Eigen::Vector3d& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        for (int c = 0; c < 8; ++c)
          points.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
      }
    };
    Progress sim_progress("simulate", run.steps);
    record();
    for (std::int64_t s = 1; s <= run.steps; ++s) {
      if (replay)
        replay->step(world, s - 1, h, file);
      else
        checked_step(world, h, file);  // checks for Ctrl-C first
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

    const bool any = !points.empty();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(any ? INFINITY : -1.0), hi = -lo;
    for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double radius = std::max(0.5, (hi - lo).norm() / 2);  // the scene's size, for grid and margins

    // Up against gravity as seen in the slice.
    Eigen::Vector3d up = -slices.to_slice_vector(scene.settings.gravity);
    if (!(up.norm() > 1e-9 * std::max(1.0, scene.settings.gravity.norm()))) up = Eigen::Vector3d::UnitY();
    up.normalize();

    // Ground: the scene's halfspace, else a grid just below everything, across gravity. The camera
    // also frames the feet of the points on it, where the shadows fall.
    render::FrameDesc frame;
    frame.ground.enabled = true;
    if (const auto g = slices.ground(world)) {
      frame.ground.normal = g->first;  // out of the solid {n . y <= offset}
      frame.ground.offset = g->second;
    } else {
      double low = any ? INFINITY : -radius;
      for (const Eigen::Vector3d& p : points) low = std::min(low, p.dot(up));
      frame.ground.normal = up;
      frame.ground.offset = low - 0.05 * radius;
    }
    frame.ground.spacing = std::pow(10.0, std::floor(std::log10(radius))) / 2;
    frame.ground.extent = 8 * radius;
    {
      const Eigen::Vector3d n = frame.ground.normal;
      const std::size_t count = points.size();
      for (std::size_t i = 0; i < count; ++i)
        points.push_back(points[i] - (n.dot(points[i]) - frame.ground.offset) * n);
    }

    // Camera: fitted to the points (90% of the narrower way), recentred on them in the picture.
    render::Camera camera;
    camera.up = up;
    camera.fov_y_degrees = scene.view.fov_degrees.value_or(40.0);
    const double tan_y = std::tan(camera.fov_y_degrees * M_PI / 360.0), tan_x = tan_y * size.width / size.height;
    const double fill = 0.9, min_depth = 0.05 * radius;
    auto vec3 = [](const std::array<double, 3>& a) { return Eigen::Vector3d(a[0], a[1], a[2]); };
    camera.target = scene.view.target ? vec3(*scene.view.target) : Eigen::Vector3d((lo + hi) / 2);
    if (scene.view.eye) {
      camera.eye = vec3(*scene.view.eye);
    } else if (!any) {
      camera.eye = camera.target + default_view_axes(up).dir * 6.0;
    } else {
      const ViewAxes ax = default_view_axes(up);
      double d = fit_distance(points, camera.target, ax, tan_x, tan_y, fill, min_depth);
      // Perspective makes the fitted picture lopsided about the target: move the target across the view
      // by the middle of the points' angular extent (a fixed point iteration; it settles in a few rounds).
      for (int round = 0; round < 6 && !scene.view.target; ++round) {
        double u_lo = INFINITY, u_hi = -INFINITY, v_lo = INFINITY, v_hi = -INFINITY;
        for (const Eigen::Vector3d& p : points) {
          const Eigen::Vector3d q = p - camera.target;
          const double depth = d - ax.dir.dot(q);
          const double u = ax.right.dot(q) / depth / tan_x, v = ax.screen_up.dot(q) / depth / tan_y;
          u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u), v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
        }
        camera.target += d * ((u_lo + u_hi) / 2 * tan_x * ax.right + (v_lo + v_hi) / 2 * tan_y * ax.screen_up);
        d = fit_distance(points, camera.target, ax, tan_x, tan_y, fill, min_depth);
      }
      camera.eye = camera.target + ax.dir * d;
    }
    const double dist = (camera.eye - camera.target).norm();
    double nearest = dist;
    for (const Eigen::Vector3d& p : points)
      nearest = std::min(nearest, (p - camera.eye).dot(camera.target - camera.eye) / dist);
    camera.near_plane = std::max(1e-3, std::min(0.02 * dist, 0.5 * nearest));
    camera.far_plane = 10 * dist + 10 * frame.ground.extent;
    frame.camera = camera;

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
                  "is drawn, as `wedge replay` does")
      ->type_name("RECORDING...")
      ->expected(1, -1);
  cmd->add_option("--subdivisions", o.subdivisions,
                  "Tessellation level of round shapes (1..64; default 16 in 3D, 8 in 4D, 4 in 5D, 2 in 6D)")
      ->type_name("S");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_render(const RenderOptions& o) {
  const StepOptions run = parse_step_options(o.scene, o.steps, o.dt, o.every);
  const Size size = parse_size(o.scene, o.size);
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
