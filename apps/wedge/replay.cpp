// wedge replay SCENE.json RECORDING... [--out STATES.jsonl] [--every K] [--events EVENTS.jsonl] [--hash]
//                                       [--until T] [--dt H] [--workers N]
//
// Replays recorded device streams (docs/recording-format.md) into a scene through an input session
// (wedge/input/session.hpp), at the scene's fixed step: each step reads the input frame at its start
// time, applies it (grabs, torques, gravity), steps, and turns the step's contact begin events into haptic
// pulses. The state lines are
// simulate's plus `gravity` and `hands`; --events writes the grabs, releases and haptic pulses. A
// replay is a pure function of (scene, recordings): the same files give the same state hash.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scenes.hpp"
#include "session_output.hpp"
#include "step_options.hpp"
#include "verbs.hpp"

namespace wedge::cli {

namespace {

template <int N>
int replay(const Json& doc, const ReplayOptions& o, const std::optional<double>& dt, std::int64_t every,
           const std::optional<double>& until, int workers) {
  const std::string& file = o.scene;
  const Scene<N> scene = load_scene<N>(doc, file);
  const double h = dt ? *dt : scene.timestep;
  World<N> world = scene.make_world(file);
  world.update_settings([&](auto& s) { s.workers = workers; });

  ReplayInput<N> replay(scene, world, o.recordings, file, h);
  const double end = until ? *until : replay.source().duration();
  const std::int64_t steps = std::int64_t(std::ceil(end / h - 1e-9));
  SessionOutput<N> output(file, o.out, o.events, every);
  output.write_state(replay.session());
  for (std::int64_t k = 0; k < steps; ++k) {
    replay.step();
    output.after_step(replay.session());
  }
  const std::string hash = hash_text(world.state_hash());
  if (o.hash) output.write_hash(world.state_hash());
  throw_if_interrupted();
  output.commit();
  if (!o.out.empty()) {
    std::printf("replayed %.3f s (%lld steps) of %s: %s, %s, %s; wrote %lld states to %s%s%s%s%s\n",
                double(steps) * h, (long long)steps, count_of(std::int64_t(o.recordings.size()), "recording").c_str(),
                count_of(output.grabs(), "grab").c_str(), count_of(output.releases(), "release").c_str(),
                count_of(output.pulses(), "haptic pulse").c_str(), (long long)(steps / every + 1), o.out.c_str(),
                o.events.empty() ? "" : " and events to ", o.events.c_str(), o.hash ? "; state hash " : "",
                o.hash ? hash.c_str() : "");
  }
  return kExitOk;
}

}  // namespace

CLI::App* add_replay_verb(CLI::App& app, ReplayOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "Replay recorded controllers and accelerometers (docs/recording-format.md) into a scene through the input "
      "layer, headless; write states as JSON Lines like simulate, plus gravity and the hands.");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("recordings", o.recordings, "Recordings (JSON Lines); several merge by time")
      ->required()
      ->type_name("RECORDING...");
  cmd->add_option("--out,-o", o.out, "Write the states to FILE (atomically) instead of stdout")->type_name("FILE");
  cmd->add_option("--every,-k", o.every, "Write every K-th step (>= 1; default 1); step 0 is always written")
      ->type_name("K");
  cmd->add_option("--events", o.events, "Write grabs, releases and haptic pulses to FILE (JSON Lines)")
      ->type_name("FILE");
  cmd->add_flag("--hash", o.hash, "After the last state, write {\"state_hash\": ...} (and print it with --out)");
  cmd->add_option("--until", o.until, "Stop at T seconds (default: the end of the recordings)")->type_name("T");
  cmd->add_option("--dt", o.dt, "Step size in seconds (default: the scene's \"timestep\", else 1/120)")
      ->type_name("H");
  cmd->add_option("--workers", o.workers,
                  "Threads per step, 1..64 (default 1); the states are bit-identical for any number")
      ->type_name("N");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_replay(const ReplayOptions& o) {
  // Options first (so that every message names the scene), then the scene and the recordings.
  const StepOptions run = parse_step_options(o.scene, "0", o.dt, o.every);
  const int workers = parse_workers(o.scene, o.workers);
  std::optional<double> until;
  if (!o.until.empty()) {
    double t = 0.0;
    if (!parse_finite(o.until, t) || !(t >= 0.0))
      throw Failure(o.scene + ": --until must be a time in seconds >= 0 (got '" + o.until + "')");
    until = t;
  }
  if (!o.out.empty() && o.out == o.events) throw Failure(o.scene + ": --out and --events must be different files");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  return with_dim(n, [&](auto dim) { return replay<decltype(dim)::value>(doc, o, run.dt, run.every, until, workers); });
}

}  // namespace wedge::cli
