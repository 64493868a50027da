#include "csv_table.hpp"

#include <csv.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "wedge/error.hpp"

namespace wedge::recordings {
namespace {

// libcsv's callbacks write here: cb1 ends a field, cb2 ends a record.
struct Collector {
  std::vector<CsvRecord> records;
  CsvRecord current;
  int line = 1;        // the line being fed to the parser
  int start_line = 1;  // the last line fed while the parser was between records
  bool in_record = false;

  static void field(void* text, std::size_t size, void* data) {
    auto& self = *static_cast<Collector*>(data);
    if (!self.in_record) {
      // (A record's first field may end lines after it began, inside quotes: the record starts on the
      // last line that was fed with no record begun.)
      self.current.line = self.start_line;
      self.in_record = true;
    }
    self.current.fields.emplace_back(static_cast<const char*>(text), size);
  }
  static void record(int, void* data) {
    auto& self = *static_cast<Collector*>(data);
    if (!self.in_record) return;  // libcsv reports no blank lines without CSV_REPALL_NL; nothing to end
    self.records.push_back(std::move(self.current));
    self.current = {};
    self.in_record = false;
  }
};

// libcsv's parser state between records (csv_parser::pstate; ROW_NOT_BEGUN in libcsv.c).
constexpr int kRowNotBegun = 0;

// libcsv's parser, freed on every path out.
struct Parser {
  csv_parser p{};
  explicit Parser(const std::string& path) {
    if (csv_init(&p, CSV_STRICT | CSV_STRICT_FINI) != 0) throw Error(path + ": cannot start the CSV parser");
  }
  ~Parser() { csv_free(&p); }
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;
};

}  // namespace

std::vector<CsvRecord> read_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw Error(path + ": read failed");
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // a UTF-8 byte-order mark from a spreadsheet

  Parser parser(path);
  Collector out;
  auto fail = [&](int line, const std::string& problem) {
    throw Error(path + ":" + std::to_string(line) + ": " + problem);
  };
  // Fed one physical line at a time, so that each record knows the line it starts on.
  for (std::size_t begin = 0; begin < text.size(); ++out.line) {
    const std::size_t newline = text.find('\n', begin);
    const std::size_t end = newline == std::string::npos ? text.size() : newline + 1;
    if (std::memchr(text.data() + begin, '\0', end - begin) != nullptr)
      fail(out.line, "a NUL byte (not a text file)");
    const std::size_t size = end - begin;
    if (parser.p.pstate == kRowNotBegun) out.start_line = out.line;
    if (csv_parse(&parser.p, text.data() + begin, size, Collector::field, Collector::record, &out) != size)
      fail(out.line, std::string("malformed CSV quoting (") + csv_strerror(csv_error(&parser.p)) +
                         "): a quote inside an unquoted field, or text after a closing quote");
    begin = end;
  }
  if (csv_fini(&parser.p, Collector::field, Collector::record, &out) != 0)
    fail(out.line - 1, "a quoted field is still open at the end of the file");
  return std::move(out.records);
}

}  // namespace wedge::recordings
