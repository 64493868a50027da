// wedge render SCENE.json --steps N [--every K] [--dt H] [--w W] --out DIR [--size WxH] [--subdivisions S]
//
// Simulates a scene and draws the 3D slice of every K-th state (step 0 included) offscreen, through
// OSMesa, into DIR/frame_00000.png, frame_00001.png, ... Everything is checked and the whole run is
// simulated before the first frame is written; if writing fails, the frames written so far are removed.
// The camera frames every body's slice over the whole run from an elevated three-quarter view with the
// scene's "down" (gravity, projected into the slice) pointing down the screen, unless the scene's
// "view" says otherwise (docs/scene-format.md).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

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

template <int N>
int render(const Json& doc, const RenderOptions& o, const StepOptions& run, const std::vector<double>& w,
           int subdivisions, const Size& size) {
  const std::string& file = o.scene;
  if constexpr (N < 3) {
    (void)doc, (void)run, (void)w, (void)subdivisions, (void)size;
    throw Failure(file + ": a 2D scene cannot be rendered (render shows 3D slices of 3D..6D scenes)");
  } else {
    const Scene<N> scene = load_scene<N>(doc, file);
    const double h = run.dt ? *run.dt : scene.timestep;
    World<N> world = scene.make_world(file);
    SceneSlices<N> slices(scene, w, subdivisions, file);

    // Simulate first: the states of the frames to draw, and the bounds of everything the camera shows.
    std::vector<std::vector<Pose<N>>> frames;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    auto record = [&] {
      std::vector<Pose<N>> poses;
      for (int i = 0; i < world.body_count(); ++i) {
        const Body<N>& b = world.body(BodyId{std::uint32_t(i)});
        poses.push_back({b.center, b.rotor});
      }
      frames.push_back(std::move(poses));
      for (std::size_t k = 0; k < slices.entries().size(); ++k)
        if (const auto ball = slices.slice_bound(world, k)) {
          lo = lo.cwiseMin(ball->first - Eigen::Vector3d::Constant(ball->second));
          hi = hi.cwiseMax(ball->first + Eigen::Vector3d::Constant(ball->second));
        }
    };
    Progress sim_progress("simulate", run.steps);
    record();
    for (std::int64_t s = 1; s <= run.steps; ++s) {
      checked_step(world, h, file);
      if (s % run.every == 0) record();
      if (s % 64 == 0) sim_progress.update(s);
    }
    sim_progress.update(run.steps);
    sim_progress.finish();

    // Camera: up against gravity as seen in the slice; target the middle of the bounds.
    Eigen::Vector3d up = -slices.to_slice_vector(scene.settings.gravity);
    if (!(up.norm() > 1e-9 * std::max(1.0, scene.settings.gravity.norm()))) up = Eigen::Vector3d::UnitY();
    up.normalize();
    const bool any = lo.x() <= hi.x();
    const Eigen::Vector3d center = any ? Eigen::Vector3d((lo + hi) / 2) : Eigen::Vector3d::Zero();
    const double radius = any ? std::max(0.5, (hi - lo).norm() / 2) : 2.0;
    render::Camera camera;
    camera.up = up;
    camera.fov_y_degrees = scene.view.fov_degrees.value_or(40.0);
    camera.target = scene.view.target ? Eigen::Vector3d((*scene.view.target)[0], (*scene.view.target)[1], (*scene.view.target)[2])
                                      : center;
    if (scene.view.eye) {
      camera.eye = Eigen::Vector3d((*scene.view.eye)[0], (*scene.view.eye)[1], (*scene.view.eye)[2]);
    } else {
      // Toward the viewer: the slice axis least aligned with up (z when up is y), then right = up x it.
      Eigen::Index axis = 0;
      (Eigen::Vector3d(0.5, 0.5, 0.0) + up.cwiseAbs()).minCoeff(&axis);  // prefers z, then x
      Eigen::Vector3d toward = Eigen::Vector3d::Unit(axis) - up * up(axis);
      toward.normalize();
      const Eigen::Vector3d right = up.cross(toward);
      const Eigen::Vector3d dir = (0.85 * toward + 0.45 * up + 0.45 * right).normalized();
      const double half_fov = camera.fov_y_degrees * M_PI / 360.0;
      const double half_fov_x = std::atan(std::tan(half_fov) * size.width / size.height);
      // The bounds' sphere just fits the narrower field of view (its rim may touch the frame's edge).
      camera.eye = camera.target + dir * (radius / std::tan(std::min(half_fov, half_fov_x)));
    }
    const double dist = (camera.eye - camera.target).norm();
    camera.near_plane = std::max(1e-3, 0.02 * dist);
    camera.far_plane = 10 * dist + 100.0;

    // Ground: the scene's halfspace, else a grid just below everything, across gravity.
    render::FrameDesc frame;
    frame.camera = camera;
    frame.ground.enabled = true;
    if (const auto g = slices.ground(scene, world)) {
      frame.ground.normal = -g->first;  // the grid faces out of the solid halfspace
      frame.ground.offset = -g->second;
    } else {
      double low = camera.target.dot(up) - radius;
      if (any)
        for (int c = 0; c < 8; ++c) {
          const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
          low = std::min(low, corner.dot(up));
        }
      frame.ground.normal = up;
      frame.ground.offset = low - 0.05 * radius;
    }
    frame.ground.spacing = std::pow(10.0, std::floor(std::log10(radius))) / 2;
    frame.ground.extent = 8 * radius;

    // Draw and write.
    render::OffscreenContext context(size.width, size.height);
    render::Renderer renderer;
    std::vector<slicing::DisplayMesh<3>> meshes;
    const fs::path dir(o.out);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw Failure(o.out + ": cannot create the output folder (" + ec.message() + ")");
    std::vector<fs::path> written;
    Progress progress("render", std::int64_t(frames.size()));
    try {
      for (std::size_t f = 0; f < frames.size(); ++f) {
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
        written.push_back(dir / name);
        render::write_png(written.back().string(), context.read_rgba(), size.width, size.height);
        progress.update(std::int64_t(f + 1));
      }
    } catch (const Error& e) {
      for (const fs::path& p : written) fs::remove(p, ec);
      throw Failure(e.what());
    }
    progress.finish();
    std::cout << "wrote " << frames.size() << " frame" << (frames.size() == 1 ? "" : "s") << " (" << size.width << "x"
              << size.height << ") to " << o.out << "\n";
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
  return with_dim(n, [&](auto dim) { return render<decltype(dim)::value>(doc, o, run, w, subdivisions, size); });
}

}  // namespace wedge::cli
