// One frame of `wedge xr` (apps/wedge/xr.cpp, XrApp) at 90 Hz, without a runtime or a headset
// (docs/performance.md, "OpenXR frame"). Each benchmark iteration plays 7.5 s of the scene, frame by frame:
//   session  the physics steps due by the frame's display time (step k runs in frame f when k h <= f / 90,
//            on the app's integer-nanosecond clock), each through input::Session::step: the input layer's
//            before_step, World::step with the app's finiteness check, after_step and its haptic pulses
//            (kept as the app keeps them for the hand's flash and the hit marks; no device to send them to)
//   slicing  HeadsetView::update (apps/wedge/xr_view.hpp): WorldSlices::slice at the app's default
//            tessellation (5 in 4D) plus the hand, hit and gauge markers, a few dozen triangles
//   drawing  both eyes: HeadsetView::eye's FrameDesc drawn by render::Renderer at 640 x 720 (the replay
//            runtime's default eye size) into an offscreen OSMesa context, then glFinish. This is Mesa's
//            software rasteriser (llvmpipe, one thread unless LP_NUM_THREADS is set), not a GPU.
// The eyes are the replay runtime's (xr/runtime/src/spaces.cpp, playback.hpp): a head 0.5 m behind the
// tracking origin at its height, looking 35 degrees down, eyes 0.0315 m to either side, fields of view
// 45 degrees left and right, 50 up and down.
//   BM_XrFrame/toy_table_grab  scenes/toy_table_4d.json driven by recordings/scripted/toy_table_grab.jsonl
//                              through RecordingSource::frame_at (as `wedge replay` does): the hand grabs,
//                              turns, knocks and throws
//   BM_XrFrame/fig2            scenes/fig2_duocylinder_4d.json, hands untracked: the duocylinder rolls
//                              into the 27 balls
// Counters, in ms per frame: the median over every frame played (676 per iteration) of each part, of
// session + slicing and of the whole frame; session_slicing_p95_ms and _max_ms show the slow frames (two
// steps, new contacts, the machine's other load). Google Benchmark's own time is a whole iteration.
// Not measured: the OpenXR calls (xrWaitFrame, xrSyncActions, locating the hands, xrApplyHapticFeedback,
// swapchains, xrEndFrame) and the state lines `wedge xr` writes every step unless --every thins them.
#include <benchmark/benchmark.h>

#include <GL/gl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "replay_input.hpp"  // (before xr_view.hpp, which uses interaction_settings)
#include "scene_slices.hpp"
#include "step_options.hpp"
#include "wedge/recordings/recording.hpp"
#include "wedge/recordings/recording_source.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/renderer.hpp"
#include "xr_view.hpp"

namespace {

using namespace wedge;
using Clock = std::chrono::steady_clock;

constexpr int kEyeWidth = 640, kEyeHeight = 720;  // the replay runtime's default (WEDGE_XR_EYE_SIZE)
constexpr std::int64_t kLastFrame = 675;          // frames 0..675: 7.5 s at 90 Hz, the recording's length
constexpr double kFlash = 0.25;                   // s: a pulse's mark stays this long (as XrApp)

// Frame n's display time, ns after frame 0: round(n 1e9 / 90) (xr/runtime/src/clock.hpp).
std::int64_t frame_ns(std::int64_t n) { return (n * 200'000'000 + 9) / 18; }
// Step k's time, ns after frame 0: round(k h 1e9) (xr::FrameClock::step_time).
std::int64_t step_ns(std::int64_t k, double h) { return std::llround(double(k) * h * 1e9); }

// Eye 0 (left) or 1 (right) as the replay runtime locates it in the tracking space.
XrView eye_view(int eye) {
  const Eigen::Quaterniond head(Eigen::AngleAxisd(-35.0 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d p = Eigen::Vector3d(0.0, 0.0, 0.5) + head * Eigen::Vector3d(eye == 0 ? -0.0315 : 0.0315, 0, 0);
  const float h = float(45.0 * std::numbers::pi / 180.0), v = float(50.0 * std::numbers::pi / 180.0);
  XrView view{};
  view.type = XR_TYPE_VIEW;
  view.pose.orientation = {float(head.x()), float(head.y()), float(head.z()), float(head.w())};
  view.pose.position = {float(p.x()), float(p.y()), float(p.z())};
  view.fov = {-h, h, v, -v};
  return view;
}

double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// The q-quantile (0..1) of the values, nearest rank.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto k = std::ptrdiff_t(std::lround(q * double(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[std::size_t(k)];
}

// Each frame's parts, in ms.
struct FrameTimes {
  std::vector<double> session, slicing, drawing, session_slicing, total;
  void add(Clock::duration s, Clock::duration sl, Clock::duration d) {
    session.push_back(ms(s));
    slicing.push_back(ms(sl));
    drawing.push_back(ms(d));
    session_slicing.push_back(ms(s + sl));
    total.push_back(ms(s + sl + d));
  }
};

void BM_XrFrame(benchmark::State& state, const char* scene_name, const char* recording_name) {
  ::setenv("LP_NUM_THREADS", "1", 0);
  const std::string root = WEDGE_SOURCE_DIR;
  const std::string file = root + "/scenes/" + scene_name;
  const scenes::Scene<4> scene = scenes::load_scene_file<4>(file);
  const std::string rec_file = *recording_name ? root + "/recordings/scripted/" + recording_name : "";
  std::optional<recordings::Recording> recording;
  if (!rec_file.empty()) recording = recordings::read_recording(rec_file);
  const int subdivisions = cli::default_play_subdivisions(cli::default_display_subdivisions(4));
  const double h = scene.timestep;

  render::OffscreenContext context(kEyeWidth, kEyeHeight);
  render::Renderer renderer;
  state.SetLabel(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  const std::array<XrView, 2> views{eye_view(0), eye_view(1)};

  FrameTimes times;
  std::int64_t steps = 0, grabs = 0, pulses = 0, frames = 0;
  double triangles = 0.0;
  for (auto _ : state) {
    state.PauseTiming();  // the scene from the start
    World<4> world = scene.make_world(file);
    input::Session<4> session(world, scenes::session_settings(scene, h));
    session.set_step_function([&file](World<4>& w, double step) { cli::step_checking_finite(w, step, file); });
    std::optional<recordings::RecordingSource> source;
    if (recording) source.emplace(std::vector<recordings::Recording>{*recording}, std::vector<std::string>{rec_file});
    cli::HeadsetView<4> view(scene, world, {0.0}, subdivisions, file);
    std::array<double, 2> flash_until{};
    std::vector<std::pair<Vec<4>, double>> marks;
    std::vector<Vec<4>> hits;
    state.ResumeTiming();

    for (std::int64_t f = 0; f <= kLastFrame; ++f) {
      const Clock::time_point t0 = Clock::now();
      while (step_ns(session.step_count(), h) <= frame_ns(f)) {
        input::InputFrame untracked;
        untracked.t = session.time();
        session.step(source ? source->frame_at(session.time()) : untracked);
        for (const input::HapticPulse<4>& p : session.pulses()) {
          flash_until[std::size_t(p.hand)] = world.time() + kFlash;
          marks.emplace_back(p.point, world.time() + kFlash);
        }
        for (const input::InteractionEvent<4>& e : session.events())
          grabs += e.kind == input::InteractionEvent<4>::Kind::Grab;
        pulses += std::int64_t(session.pulses().size());
        session.clear_output();
        ++steps;
      }
      const Clock::time_point t1 = Clock::now();
      std::erase_if(marks, [&](const auto& m) { return m.second <= world.time(); });
      hits.clear();
      for (const auto& m : marks) hits.push_back(m.first);
      view.update(world, session.interaction(), flash_until, hits);
      const Clock::time_point t2 = Clock::now();
      for (std::size_t e = 0; e < views.size(); ++e) {
        const render::FrameDesc frame = view.eye(views[e]);
        renderer.draw(frame, kEyeWidth, kEyeHeight);
        if (e == 0)
          for (const render::MeshDraw& m : frame.meshes) triangles += double(m.mesh->cells.size());
      }
      glFinish();
      const Clock::time_point t3 = Clock::now();
      times.add(t1 - t0, t2 - t1, t3 - t2);
      ++frames;
    }
    benchmark::DoNotOptimize(world.state_hash());
  }
  if (recording && grabs == 0) state.SkipWithError("the recording grabbed nothing");
  state.counters["session_ms"] = quantile(times.session, 0.5);
  state.counters["slicing_ms"] = quantile(times.slicing, 0.5);
  state.counters["session_slicing_ms"] = quantile(times.session_slicing, 0.5);
  state.counters["session_slicing_p95_ms"] = quantile(times.session_slicing, 0.95);
  state.counters["session_slicing_max_ms"] = quantile(times.session_slicing, 1.0);
  state.counters["drawing_ms"] = quantile(times.drawing, 0.5);
  state.counters["total_ms"] = quantile(times.total, 0.5);
  state.counters["steps_per_frame"] = double(steps) / double(frames);
  state.counters["triangles_per_eye"] = triangles / double(frames);
  state.counters["grabs"] = double(grabs) / double(state.iterations());
  state.counters["pulses"] = double(pulses) / double(state.iterations());
}

}  // namespace

BENCHMARK_CAPTURE(BM_XrFrame, toy_table_grab, "toy_table_4d.json", "toy_table_grab.jsonl")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_XrFrame, fig2, "fig2_duocylinder_4d.json", "")->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
