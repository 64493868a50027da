// wedge xr SCENE.json [--headless] [--record FILE] [--out FILE] [--every K] [--events FILE] [--hash]
//                     [--w W] [--subdivisions S] [--until T]
//
// The scene in a headset, through OpenXR and whatever runtime is active (docs/xr.md). Each frame:
//   xrWaitFrame -> the frame's display time (clock.hpp) -> xrSyncActions -> for every physics step due
//   by that time: both hands located at the step's own time -> input::Session::step -> each haptic
//   pulse out through xrApplyHapticFeedback on its hand -> (rendering: both eyes' views of the slice)
// The input session is the one `wedge replay` runs, so `--record` writes the hands as the physics used
// them, one sample per step, and `wedge replay SCENE FILE` ends in the state hash `--hash` printed.
// --headless runs input, physics and haptics with no frames (XR_MND_headless): for CI and recording.
// Ctrl-C asks the runtime to end the session; the outputs and the recording are then written whole.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "fp_traps.hpp"
#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scenes.hpp"
#include "session_output.hpp"
#include "step_options.hpp"
#include "verbs.hpp"
#include "wedge/recordings/recording.hpp"
#include "wedge/scenes/interaction.hpp"
#include "wedge/xr/check.hpp"
#include "wedge/xr/clock.hpp"
#include "wedge/xr/controllers.hpp"
#include "wedge/xr/instance.hpp"
#include "wedge/xr/graphics.hpp"
#include "wedge/xr/session.hpp"
#include "xr_view.hpp"

namespace wedge::cli {

namespace {

void log_line(const std::string& text) { std::cerr << "wedge xr: " << text << "\n"; }

struct XrRun {
  std::int64_t every = 1;
  std::optional<double> until;
  std::vector<double> offsets;  // the slice's initial offsets (--w)
  int subdivisions = 0;
};

// The recording of a live session: each step's hands (as the physics used them) and the head.
class SessionRecorder {
 public:
  explicit SessionRecorder(const std::string& path) : writer_(path, "xr") {}
  void frame(const input::InputFrame& f) { writer_.write_frame(f); }
  void head(double t, const input::Pose& pose) { writer_.write(input::HeadSample{t, pose}); }
  void close() { writer_.close(); }

 private:
  recordings::RecordingWriter writer_;
};

// Runs an OpenXR call site's constructor, turning its failure into the verb's one-line error.
template <class F>
void opening(const std::string& file, F&& f) {
  try {
    f();
  } catch (const xr::XrError& e) {
    throw Failure(file + ": " + e.what());
  } catch (const Error& e) {
    throw Failure(file + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw Failure(file + ": " + e.what());
  }
}

// The app: the scene's world and input session, the OpenXR objects, and the frame loop's stages.
template <int N>
class XrApp {
 public:
  XrApp(const Scene<N>& scene, const XrOptions& o, const XrRun& run)
      : scene_(scene), o_(o), run_(run), world_(scene.make_world(o.scene)), output_(o.scene, o.out, o.events, run.every) {
    start_session();
    open_xr();
    if (!o.record.empty()) opening(o.scene, [&] { recorder_.emplace(o.record); });
  }

  // The frame loop, until the runtime ends the session (or --until, or Ctrl-C, asks it to).
  void run() {
    output_.write_state(*session_);
    while (true) {
      check_signal();
      if (xs_->poll_events()) controllers_->log_profiles();
      if (xs_->done()) break;
      if (!xs_->running()) {  // (before READY, or between STOPPING and EXITING)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      const XrFrameState frame = xs_->wait_frame();
      const XrTime now = frame_time(frame);
      controllers_->sync();
      if (controllers_->reset_pressed()) reset();
      step_to(now);
      if (!o_.headless) draw(frame, now);
    }
  }

  // The outputs written whole, and the closing line.
  void finish() {
    const std::uint64_t hash = world_.state_hash();
    if (o_.hash) output_.write_hash(hash);
    if (recorder_) opening(o_.scene, [&] { recorder_->close(); });
    output_.commit();
    std::printf("xr session on '%s' (%s): %.3f s, %lld steps; %s, %s, %s%s%s; ended: %s\n",
                instance_->runtime_name().c_str(), o_.headless ? "headless" : "rendered", session_->time(),
                (long long)session_->step_count(), count_of(output_.grabs(), "grab").c_str(),
                count_of(output_.releases(), "release").c_str(), count_of(output_.pulses(), "haptic pulse").c_str(),
                o_.hash ? "; state hash " : "", o_.hash ? hash_text(hash).c_str() : "", xs_->end_reason().c_str());
  }

 private:
  // The input session over the world; Ctrl-C must end the OpenXR session cleanly, not unwind from inside
  // a step, so the step checks only finiteness.
  void start_session() {
    session_.emplace(make_session(scene_, world_, scene_.timestep, o_.scene));
    session_->set_step_function([this](World<N>& w, double h) { step_checking_finite(w, h, o_.scene); });
    session_->set_observer([this](const input::InputFrame& f) {
      if (recorder_) recorder_->frame(f);
    });
  }

  // Instance, (GL context,) session, actions, (swapchains, renderer, the headset's view).
  void open_xr() {
    xr::InstanceOptions options;
    options.headless = o_.headless;
    opening(o_.scene, [&] { instance_.emplace(options); });
    log_line("runtime '" + instance_->runtime_name() + "', system '" + instance_->system_name() + "'" +
             (o_.headless ? " (headless)" : ""));
    if (!o_.headless) opening(o_.scene, [&] { gl_.emplace(*instance_); });
    opening(o_.scene, [&] {
      xs_.emplace(*instance_, gl_ ? gl_->binding() : nullptr, log_line);
      controllers_.emplace(*instance_, *xs_, log_line);
    });
    if constexpr (N >= 3) {  // (a 2D scene runs headless only: run_xr_scene says so)
      if (o_.headless) return;
      opening(o_.scene, [&] {
        eyes_.emplace(*instance_, *xs_);
        renderer_.emplace();
        std::vector<double> w = run_.offsets;
        w.resize(std::size_t(std::max(N - 3, 0)), 0.0);
        view_.emplace(scene_, world_, w, run_.subdivisions, o_.scene);
      });
      follow_slice();
      log_line("drawing " + std::to_string(eyes_->width(0)) + "x" + std::to_string(eyes_->height(0)) + " per eye");
    }
  }

  void check_signal() {
    if (signal_ || (signal_ = interrupt_signal()) == 0) return;
    log_line(std::string("interrupted (") + (signal_ == SIGINT ? "SIGINT" : signal_ == SIGTERM ? "SIGTERM" : "SIGHUP") +
             "): ending the session");
    xs_->request_exit();
  }

  XrTime frame_time(const XrFrameState& frame) {
    const XrTime now = clock_.frame_time(frame, instance_->now());
    if (clock_.paced() && !paced_logged_) {
      paced_logged_ = true;
      log_line("the runtime's frame times are not usable (predictedDisplayTime " +
               std::to_string(frame.predictedDisplayTime) + "): pacing on the runtime's clock");
    }
    return now;
  }

  // The physics steps due by this frame's display time, each with the hands located at its own time;
  // the pulses go out to the controllers as they come.
  void step_to(XrTime now) {
    const TrappedSteps trapped;  // WEDGE_FP_TRAPS=1: the steps run with traps on, the drawing without
    const double h = scene_.timestep;
    while (clock_.step_time(session_->step_count(), h) <= now) {
      if (run_.until && session_->time() >= *run_.until - 1e-9) {
        xs_->request_exit();
        return;
      }
      const XrTime at = clock_.step_time(session_->step_count(), h);
      input::InputFrame f;
      f.t = session_->time();
      for (int k = 0; k < input::kHandCount; ++k) f.hands[std::size_t(k)] = controllers_->hand_at(k, at);
      session_->step(f);
      if (recorder_)
        if (const auto head = controllers_->head_at(at)) recorder_->head(f.t, *head);
      for (const input::HapticPulse<N>& p : session_->pulses()) {
        controllers_->pulse(p.hand, p.amplitude, p.duration, p.frequency);
        if (!o_.headless) {  // (marks for the eyes; nothing draws them headless)
          flash_until_[std::size_t(p.hand)] = world_.time() + kFlash;
          hits_.emplace_back(p.point, world_.time() + kFlash);
        }
      }
      output_.after_step(*session_);
    }
  }

  // Both eyes' views of the slice into their swapchain images, submitted as one projection layer (none
  // when the runtime says not to render or does not know where the head is).
  void draw(const XrFrameState& frame, XrTime now) {
    if constexpr (N >= 3) draw_eyes(frame, now);
  }
  void draw_eyes(const XrFrameState& frame, XrTime now) {
    const double dt = last_draw_ ? double(now - last_draw_) * 1e-9 : 0.0;
    last_draw_ = now;
    if (view_->move_offsets(controllers_->slice_rate(), dt)) follow_slice();
    if (!xs_->begin_frame()) return;
    const XrTime display = frame.predictedDisplayTime > 0 ? frame.predictedDisplayTime : now;
    std::vector<const XrCompositionLayerBaseHeader*> layers;
    if (frame.shouldRender && eyes_->locate(display)) {
      std::erase_if(hits_, [&](const auto& h) { return h.second <= world_.time(); });
      std::vector<Vec<N>> hits;
      for (const auto& h : hits_) hits.push_back(h.first);
      view_->update(world_, session_->interaction(), flash_until_, hits);
      for (int e = 0; e < xr::EyeSwapchains::kEyes; ++e) {
        eyes_->begin_eye(e);
        renderer_->draw(view_->eye(eyes_->view(e)), eyes_->width(e), eyes_->height(e));
        eyes_->end_eye(e);
      }
      layers.push_back(eyes_->layer());
    }
    xs_->end_frame(display, layers);
  }

  // The hands act in the slice shown (the tracking origin's hidden coordinates are the slice offsets),
  // except while recording: a recording carries no slice, so the hands stay in the scene's own, as
  // `wedge view --record` does, and `wedge replay` of the file means the same.
  void follow_slice() {
    if constexpr (N >= 4) {
      if (recorder_) return;
      Vec<N> origin = scenes::interaction_settings(scene_).tracking.origin;
      const std::vector<double>& w = view_->offsets();
      for (std::size_t i = 0; i < w.size(); ++i) origin[N - 1 - int(i)] = w[i];
      session_->set_tracking_origin(origin);
    }
  }

  // The reset button: the scene from the start (not while recording: the recording could not say so).
  void reset() {
    if (recorder_) {
      log_line("reset ignored: --record is on, and a recording cannot hold a reset");
      return;
    }
    log_line("reset");
    world_ = scene_.make_world(o_.scene);
    start_session();
    if constexpr (N >= 3)
      if (view_) follow_slice();
  }

  static constexpr double kFlash = 0.25;  // s: a pulse's mark stays this long

  const Scene<N>& scene_;
  const XrOptions& o_;
  XrRun run_;
  World<N> world_;
  std::optional<input::Session<N>> session_;
  SessionOutput<N> output_;
  std::optional<SessionRecorder> recorder_;
  std::optional<xr::Instance> instance_;
  std::optional<xr::GlContext> gl_;
  std::optional<xr::Session> xs_;
  std::optional<xr::Controllers> controllers_;
  std::optional<xr::EyeSwapchains> eyes_;
  std::optional<render::Renderer> renderer_;
  std::optional<std::conditional_t<(N >= 3), HeadsetView<N>, int>> view_;  // (none in 2D)
  xr::FrameClock clock_;
  bool paced_logged_ = false;
  int signal_ = 0;
  XrTime last_draw_ = 0;
  std::array<double, 2> flash_until_{};
  std::vector<std::pair<Vec<N>, double>> hits_;
};

template <int N>
int run_xr_scene(const Json& doc, const XrOptions& o, const XrRun& run) {
  const Scene<N> scene = load_scene<N>(doc, o.scene);
  if (N < 3 && !o.headless)
    throw Failure(o.scene + ": a 2D scene has no 3D slice to show in a headset (run it --headless, or a 3D..6D scene)");
  std::optional<MesaArithmetic> mesa;  // the eyes draw through Mesa; step_to traps the steps (fp_traps.hpp)
  if (!o.headless) mesa.emplace();
  XrApp<N> app(scene, o, run);
  app.run();
  app.finish();
  return kExitOk;
}

}  // namespace

CLI::App* add_xr_verb(CLI::App& app, XrOptions& o) {
  CLI::App* cmd = app.add_subcommand("xr", kXrSummary);
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_flag("--headless", o.headless, "No frames: input, physics and haptics only (needs XR_MND_headless)");
  cmd->add_option("--record", o.record,
                  "Record the session to FILE (docs/recording-format.md) as it runs, line by line; `wedge replay "
                  "SCENE FILE` ends in the same state")
      ->type_name("FILE");
  cmd->add_option("--out,-o", o.out, "Write the states as JSON Lines to FILE (as wedge replay does)")->type_name("FILE");
  cmd->add_option("--every,-k", o.every, "Write every K-th step (>= 1; default 1); step 0 is always written")
      ->type_name("K");
  cmd->add_option("--events", o.events, "Write grabs, releases and haptic pulses to FILE (JSON Lines)")
      ->type_name("FILE");
  cmd->add_flag("--hash", o.hash, "At the end, write {\"state_hash\": ...} after the states and print it");
  cmd->add_option("--w", o.w, "Slice offsets to start at: W in 4D, W1,W2 in 5D, three in 6D (default 0); the "
                  "thumbstick moves the first")
      ->type_name("W");
  cmd->add_option("--subdivisions", o.subdivisions, "Tessellation of round shapes (default 5 in 4D)")->type_name("S");
  cmd->add_option("--until", o.until, "End the session at T seconds (default: when the runtime ends it)")
      ->type_name("T");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_xr(const XrOptions& o) {
  const StepOptions step = parse_step_options(o.scene, "0", "", o.every);
  XrRun run;
  run.every = step.every;
  if (!o.until.empty()) {
    double t = 0.0;
    if (!parse_finite(o.until, t) || !(t >= 0.0))
      throw Failure(o.scene + ": --until must be a time in seconds >= 0 (got '" + o.until + "')");
    run.until = t;
  }
  const std::vector<std::string> files = {o.out, o.events, o.record};
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = i + 1; j < files.size(); ++j)
      if (!files[i].empty() && files[i] == files[j])
        throw Failure(o.scene + ": --out, --events and --record must name different files");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  run.offsets = parse_slice_offsets(o.scene, o.w, n);
  run.subdivisions = o.subdivisions.empty() ? default_play_subdivisions(default_display_subdivisions(n))
                                            : parse_subdivisions(o.scene, o.subdivisions, n);
  return with_dim(n, [&](auto dim) { return run_xr_scene<decltype(dim)::value>(doc, o, run); });
}

}  // namespace wedge::cli
