// A CSV file read as RFC 4180 says and as real tools write it (spreadsheets, R's write.csv, pandas): quoted
// fields with embedded commas, quotes ("") and line breaks, CRLF or LF, a UTF-8 byte-order mark, a last
// line with or without its newline, blank lines anywhere. The parsing is libcsv's (Debian: libcsv-dev), in
// strict mode; this file only adds line numbers and errors that name the file.
#pragma once

#include <string>
#include <vector>

namespace wedge::recordings {

struct CsvRecord {
  int line = 0;                     // 1-based line of the file on which the record starts
  std::vector<std::string> fields;  // unquoted; spaces around unquoted fields removed
};

// Every non-blank record of the file, the header first. Throws wedge::Error "PATH: cannot open file", or
// "PATH:LINE: ..." for malformed quoting (a quote inside an unquoted field, text after a closing quote, a
// quote left open at the end of the file) or a NUL byte (a binary file is not CSV).
std::vector<CsvRecord> read_csv(const std::string& path);

}  // namespace wedge::recordings
