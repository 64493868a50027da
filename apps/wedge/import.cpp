// wedge import questset|coremotion SOURCE.csv --out RECORDING.jsonl
//
// Converts another device's recording into Wedge's recording format (docs/recording-format.md) with the
// importers of wedge_recordings: a Quest 2 Touch CSV in questset's layout, or an iPhone CoreMotion CSV.
// The output appears whole or not at all (write_recording renames a temporary file into place).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli_error.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"
#include "wedge/error.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::cli {

CLI::App* add_import_verb(CLI::App& app, ImportOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "import", "Convert a device recording (Quest 2 Touch CSV or iPhone CoreMotion CSV) to a Wedge recording.");
  cmd->add_option("format", o.format, "Source format: questset (Quest 2 Touch CSV) or coremotion (iPhone CSV)")
      ->required()
      ->type_name("FORMAT");
  cmd->add_option("source", o.source, "The device's CSV file")->required()->type_name("SOURCE.csv");
  cmd->add_option("--out,-o", o.out, "The recording to write (JSON Lines, docs/recording-format.md; atomically)")
      ->required()
      ->type_name("RECORDING.jsonl");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_import(const ImportOptions& o) {
  if (o.format != "questset" && o.format != "coremotion")
    throw Failure("unknown recording format '" + o.format + "' (the formats are questset and coremotion)");
  recordings::Recording r;
  try {
    r = o.format == "questset" ? recordings::import_questset_csv(o.source)
                               : recordings::import_coremotion_csv(o.source);
    throw_if_interrupted();
    recordings::write_recording(o.out, r);
  } catch (const Error& e) {  // the importers and the writer name the file (and the line) themselves
    throw Failure(e.what());
  }
  // A questset row is one head sample and one sample per hand; a CoreMotion row is one motion sample.
  const std::size_t rows = o.format == "questset" ? r.heads.size() : r.motion.size();
  std::printf("imported %zu rows from %s (hands: %zu samples, head: %zu, motion: %zu; %.1f s) to %s\n", rows,
              o.source.c_str(), r.hands.size(), r.heads.size(), r.motion.size(), r.duration(), o.out.c_str());
  return kExitOk;
}

}  // namespace wedge::cli
