// A device CSV imported as `wedge import FORMAT SOURCE.csv --out RECORDING.jsonl` does: libcsv's RFC 4180
// parsing, the columns, the numbers and the checks, and the recording written. Built once per format
// (WEDGE_FUZZ_IMPORT_FORMAT: questset, coremotion).
#include "fuzz_input.hpp"
#include "verbs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, "source.csv");
  wedge::cli::ImportOptions o;
  o.format = WEDGE_FUZZ_IMPORT_FORMAT;
  o.source = path;
  o.out = (fuzz::work_dir() / "imported.jsonl").string();
  fuzz::expect_success_or_refusal(path, [&] { wedge::cli::run_import(o); });
  return 0;
}
