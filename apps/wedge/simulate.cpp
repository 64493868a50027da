// wedge simulate SCENE.json --steps N [--dt H] [--every K] [--out FILE] [--hash] [--workers N]
//
// Loads a scene, steps the world N times with step H and writes one JSON object per line (JSON Lines)
// for step 0 and every K-th step: time, total energy, momenta and every body's state. With --hash a final
// line {"state_hash": "<16 hex digits>"} carries World::state_hash() after the last step. --workers
// splits each step over N threads; the states are bit-identical for any N.
// Formats: docs/scene-format.md.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>

#include "interrupt.hpp"
#include "json_out.hpp"
#include "state_json.hpp"
#include "scenes.hpp"
#include "step_options.hpp"
#include "verbs.hpp"

namespace wedge::cli {

namespace {

template <int N>
int simulate(const Json& doc, const SimulateOptions& options, const StepOptions& run, int workers) {
  const std::string& file = options.scene;
  const Scene<N> scene = load_scene<N>(doc, file);
  const double h = run.dt ? *run.dt : scene.timestep;
  World<N> world = scene.make_world(file);
  world.update_settings([&](auto& s) { s.workers = workers; });

  OutputSink out(options.out);  // nothing appears at --out unless the whole run succeeds
  auto emit = [&](const OutJson& line) {
    check_finite_line(line, world, file);
    out.write_line(line.dump());
  };

  emit(state_line(world));
  for (std::int64_t s = 1; s <= run.steps; ++s) {
    checked_step(world, h, file);
    if (s % run.every == 0) emit(state_line(world));
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, world.state_hash());
  if (options.hash) {
    OutJson line;
    line["state_hash"] = hex;
    out.write_line(line.dump());
  }
  throw_if_interrupted();
  out.commit();
  if (!options.out.empty()) {  // the states went to the file: say where, and show the hash
    const std::int64_t lines = run.steps / run.every + 1;
    std::printf("wrote %lld state%s (steps 0..%lld) to %s%s%s\n", (long long)lines, lines == 1 ? "" : "s",
                (long long)run.steps, options.out.c_str(), options.hash ? "; state hash " : "",
                options.hash ? hex : "");
  }
  return kExitOk;
}

}  // namespace

CLI::App* add_simulate_verb(CLI::App& app, SimulateOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Step a scene and write its state as JSON Lines: step 0 and every K-th step up to N.");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--steps,-n", o.steps, "Number of steps to run (required, >= 0)")->type_name("N");
  cmd->add_option("--dt", o.dt, "Step size in seconds (> 0; default: the scene's \"timestep\", else 1/120)")
      ->type_name("H");
  cmd->add_option("--every,-k", o.every, "Write every K-th step (>= 1; default 1); step 0 is always written")
      ->type_name("K");
  cmd->add_option("--out,-o", o.out, "Write to FILE (atomically: all or nothing) instead of stdout")
      ->type_name("FILE");
  cmd->add_flag("--hash", o.hash,
                "After the last state, write a line {\"state_hash\": \"<16 hex digits>\"} "
                "(World::state_hash of the final state)");
  cmd->add_option("--workers", o.workers,
                  "Threads per step, 1..64 (default 1); the states are bit-identical for any number")
      ->type_name("N");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_simulate(const SimulateOptions& o) {
  const StepOptions run = parse_step_options(o.scene, o.steps, o.dt, o.every);
  const int workers = parse_workers(o.scene, o.workers);
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  return with_dim(n, [&](auto dim) { return simulate<decltype(dim)::value>(doc, o, run, workers); });
}

}  // namespace wedge::cli
