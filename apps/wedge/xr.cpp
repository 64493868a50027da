// wedge xr SCENE.json [--headless] [--record FILE] [--out FILE] [--every K] [--events FILE] [--hash]
//                     [--until T]
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

#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scene_json.hpp"
#include "session_output.hpp"
#include "step_options.hpp"
#include "verbs.hpp"
#include "wedge/recordings/recording.hpp"
#include "wedge/xr/check.hpp"
#include "wedge/xr/clock.hpp"
#include "wedge/xr/controllers.hpp"
#include "wedge/xr/instance.hpp"
#include "wedge/xr/session.hpp"

namespace wedge::cli {

namespace {

void log_line(const std::string& text) { std::cerr << "wedge xr: " << text << "\n"; }

struct XrRun {
  std::int64_t every = 1;
  std::optional<double> until;
};

// The recording of a live session: each step's hands (as the physics used them) and the head.
class SessionRecorder {
 public:
  explicit SessionRecorder(const std::string& path) : writer_(path, "xr") {}
  void frame(const input::InputFrame& f) { writer_.write_frame(f); }
  void head(double t, const input::Pose& pose) { writer_.write(input::HeadSample{t, pose}); }
  void close() { writer_.close(); }
  std::int64_t samples() const { return writer_.samples(); }

 private:
  recordings::RecordingWriter writer_;
};

template <int N>
int run_xr_scene(const Json& doc, const XrOptions& o, const XrRun& run) {
  const std::string& file = o.scene;
  const Scene<N> scene = load_scene<N>(doc, file);
  const double h = scene.timestep;
  World<N> world = scene.make_world(file);
  input::Session<N> session = make_session(scene, world, h, file);
  // Ctrl-C must end the session cleanly, not unwind from inside a step: the step checks only finiteness.
  session.set_step_function([&file](World<N>& w, double step) { step_checking_finite(w, step, file); });
  SessionOutput<N> output(file, o.out, o.events, run.every);

  // OpenXR: instance, system, session, actions.
  xr::InstanceOptions options;
  options.headless = o.headless;
  std::optional<xr::Instance> instance;
  try {
    instance.emplace(options);
  } catch (const xr::XrError& e) {
    throw Failure(file + ": " + e.what());
  }
  log_line("runtime '" + instance->runtime_name() + "', system '" + instance->system_name() + "'" +
           (o.headless ? " (headless)" : ""));
  if (!o.headless)
    throw Failure(file + ": rendering to a headset is not built yet in this version; run with --headless");
  std::optional<xr::Session> xs;
  std::optional<xr::Controllers> controllers;
  try {
    xs.emplace(*instance, nullptr, log_line);
    controllers.emplace(*instance, *xs, log_line);
  } catch (const xr::XrError& e) {
    throw Failure(file + ": " + e.what());
  }

  std::optional<SessionRecorder> recorder;
  if (!o.record.empty()) {
    try {
      recorder.emplace(o.record);
    } catch (const Error& e) {
      throw Failure(e.what());
    }
    session.set_observer([&recorder](const input::InputFrame& f) { recorder->frame(f); });
  }

  output.write_state(session);
  xr::FrameClock clock;
  bool paced_logged = false;
  int signal = 0;
  while (true) {
    if (!signal && (signal = interrupt_signal()) != 0) {
      log_line(std::string("interrupted (") + (signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "SIGHUP") +
               "): ending the session");
      xs->request_exit();
    }
    if (xs->poll_events()) controllers->log_profiles();
    if (xs->done()) break;
    if (!xs->running()) {  // (before READY, or between STOPPING and EXITING)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    const XrFrameState frame = xs->wait_frame();
    const XrTime now = clock.frame_time(frame, instance->now());
    if (clock.paced() && !paced_logged) {
      paced_logged = true;
      log_line("the runtime's frame times are not usable (predictedDisplayTime " +
               std::to_string(frame.predictedDisplayTime) + "): pacing on the runtime's clock");
    }
    controllers->sync();
    // The physics steps due by this frame's display time, each with the hands located at its own time.
    while (clock.step_time(session.step_count(), h) <= now) {
      if (run.until && session.time() >= *run.until - 1e-9) {
        xs->request_exit();
        break;
      }
      const XrTime at = clock.step_time(session.step_count(), h);
      input::InputFrame f;
      f.t = session.time();
      for (int k = 0; k < input::kHandCount; ++k) f.hands[std::size_t(k)] = controllers->hand_at(k, at);
      session.step(f);
      if (recorder)
        if (const auto head = controllers->head_at(at)) recorder->head(f.t, *head);
      for (const input::HapticPulse<N>& p : session.pulses())
        controllers->pulse(p.hand, p.amplitude, p.duration, p.frequency);
      output.after_step(session);
    }
  }

  const std::string hash = hash_text(world.state_hash());
  if (o.hash) output.write_hash(world.state_hash());
  if (recorder) {
    try {
      recorder->close();
    } catch (const Error& e) {
      throw Failure(e.what());
    }
  }
  output.commit();
  std::printf("xr session on '%s' (%s): %.3f s, %lld steps; %s, %s, %s%s%s; ended: %s\n",
              instance->runtime_name().c_str(), o.headless ? "headless" : "rendered", session.time(),
              (long long)session.step_count(), count_of(output.grabs(), "grab").c_str(),
              count_of(output.releases(), "release").c_str(), count_of(output.pulses(), "haptic pulse").c_str(),
              o.hash ? "; state hash " : "", o.hash ? hash.c_str() : "", xs->end_reason().c_str());
  return kExitOk;
}

}  // namespace

CLI::App* add_xr_verb(CLI::App& app, XrOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "xr",
      "Put the scene in a headset through OpenXR (the active runtime, or XR_RUNTIME_JSON): grab, turn and throw "
      "with the controllers, feel the hits. --headless runs input, physics and haptics without frames.");
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
    if (!parse_double(o.until, t) || !(t >= 0.0) || !std::isfinite(t))
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
  return with_dim(n, [&](auto dim) { return run_xr_scene<decltype(dim)::value>(doc, o, run); });
}

}  // namespace wedge::cli
