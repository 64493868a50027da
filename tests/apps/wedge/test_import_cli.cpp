// `wedge import`, run as a user would: the shipped device files convert to recordings that read back as
// the library's own import, bit for bit; every failure is one line on stderr naming the file, the line and
// the problem, exit code 2, and leaves no output behind (an existing output file is left as it was).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "csv_dialects.hpp"
#include "recording_checks.hpp"
#include "wedge/recordings/recording.hpp"

namespace {

using namespace cli_runner;
using recording_checks::first_difference;
namespace rec = wedge::recordings;

const std::string kQuestCsv = std::string(WEDGE_SOURCE_DIR) + "/recordings/quest2/sample_movement_data.csv";
const std::string kCoreMotionCsv = std::string(WEDGE_SOURCE_DIR) + "/recordings/coremotion/kinetic_tremor_data.csv";

// A failure as main reports it: exit code 2, one line on stderr containing `message`, and the folder holding
// exactly `files` afterwards.
void check_failure(const TempDir& dir, const Result& r, const std::string& message, std::vector<std::string> files) {
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("wedge: ", 0) == 0);
  CHECK(r.err.find(message) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  std::sort(files.begin(), files.end());
  CHECK(dir.listing() == files);
}

}  // namespace

TEST_CASE("wedge import questset: the shipped Quest 2 trace", "[cli][recordings]") {
  TempDir dir;
  const Result r = dir.run("import questset '" + kQuestCsv + "' --out quest.jsonl");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());
  CHECK(r.out == "imported 7942 rows from " + kQuestCsv +
                     " (hands: 15884 samples, head: 7942, motion: 0; 132.3 s) to quest.jsonl\n");
  CHECK(dir.listing() == std::vector<std::string>{"quest.jsonl"});
  const rec::Recording written = rec::read_recording((dir.path() / "quest.jsonl").string());
  CHECK(written.source == "quest2-touch");
  CHECK(first_difference(written, rec::import_questset_csv(kQuestCsv)) == "");
}

TEST_CASE("wedge import coremotion: the shipped iPhone trace", "[cli][recordings]") {
  TempDir dir;
  const Result r = dir.run("import coremotion '" + kCoreMotionCsv + "' -o phone.jsonl");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out == "imported 869 rows from " + kCoreMotionCsv +
                     " (hands: 0 samples, head: 0, motion: 869; 9.4 s) to phone.jsonl\n");
  const rec::Recording written = rec::read_recording((dir.path() / "phone.jsonl").string());
  CHECK(first_difference(written, rec::import_coremotion_csv(kCoreMotionCsv)) == "");
}

// The defect, as a user met it: a CoreMotion export written by R's write.csv (every header name
// quoted, a row-name column) imports to the same recording as the plain file.
TEST_CASE("wedge import coremotion: an export written by R's write.csv", "[cli][recordings]") {
  TempDir dir;
  dir.write("r_export.csv", csv_dialects::r_write_csv(read_file(kCoreMotionCsv)));
  REQUIRE(read_file(dir.path() / "r_export.csv").rfind("\"\",\"magneticField.y\",", 0) == 0);
  const Result r = dir.run("import coremotion r_export.csv -o phone.jsonl");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("imported 869 rows") == 0);
  const rec::Recording written = rec::read_recording((dir.path() / "phone.jsonl").string());
  CHECK(first_difference(written, rec::import_coremotion_csv(kCoreMotionCsv)) == "");
}

TEST_CASE("wedge import: failures name the file, the line and the problem, and leave no output", "[cli][recordings]") {
  TempDir dir;
  std::string header, first_row;
  {
    std::ifstream in(kQuestCsv);
    std::getline(in, header);
    std::getline(in, first_row);
  }
  std::string bad_row = first_row;  // the time column is the last
  bad_row.replace(bad_row.rfind(',') + 1, std::string::npos, "soon");
  dir.write("bad.csv", header + "\n" + first_row + "\n" + bad_row + "\n");
  check_failure(dir, dir.run("import questset bad.csv --out out.jsonl"),
                "bad.csv:3: time is not a finite number ('soon')", {"bad.csv"});
  check_failure(dir, dir.run("import coremotion bad.csv --out out.jsonl"), "bad.csv:1: no column", {"bad.csv"});
  check_failure(dir, dir.run("import vive bad.csv --out out.jsonl"),
                "unknown recording format 'vive' (the formats are questset and coremotion)", {"bad.csv"});
  check_failure(dir, dir.run("import questset missing.csv --out out.jsonl"), "missing.csv: cannot open file",
                {"bad.csv"});
  check_failure(dir, dir.run("import questset '" + kQuestCsv + "' --out no/such/dir.jsonl"), "no/such/dir.jsonl",
                {"bad.csv"});
  // --out is required: a usage error, exit code 2 as well.
  const Result no_out = dir.run("import questset bad.csv");
  CHECK(no_out.code == 2);
  CHECK(no_out.err.find("--out") != std::string::npos);

  // A failed import leaves an existing output file as it was.
  dir.write("out.jsonl", "keep me\n");
  check_failure(dir, dir.run("import questset bad.csv --out out.jsonl"), "bad.csv:3:", {"bad.csv", "out.jsonl"});
  CHECK(read_file(dir.path() / "out.jsonl") == "keep me\n");
}

TEST_CASE("wedge import: listed in the help", "[cli][recordings]") {
  TempDir dir;
  CHECK(dir.run("--help").out.find("import") != std::string::npos);
  const Result r = dir.run("import --help");
  CHECK(r.code == 0);
  CHECK(r.out.find("questset") != std::string::npos);
  CHECK(r.out.find("coremotion") != std::string::npos);
  const Result unknown = dir.run("imprt questset x.csv");
  CHECK(unknown.code == 2);
  CHECK(unknown.err.find("import") != std::string::npos);  // in the list of verbs
}
