// One CSV table written the ways real tools write it, for the importers' dialect tests: each rewrite
// holds the same values as the plain file, so an importer must read every one to the same samples.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace csv_dialects {

// The plain file's rows (LF or CRLF; no quoting in it), split at commas.
inline std::vector<std::vector<std::string>> rows_of(const std::string& plain) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(plain);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::size_t begin = 0;
    for (std::size_t comma; (comma = line.find(',', begin)) != std::string::npos; begin = comma + 1)
      fields.push_back(line.substr(begin, comma - begin));
    fields.push_back(line.substr(begin));
    rows.push_back(fields);
  }
  return rows;
}

inline std::string quoted(const std::string& field) {
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// R's write.csv: a first column of row names with an empty quoted header, every header name and row name
// quoted, numbers bare, LF endings.
inline std::string r_write_csv(const std::string& plain) {
  const auto rows = rows_of(plain);
  std::string out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out += r == 0 ? "\"\"" : quoted(std::to_string(r));
    for (const std::string& f : rows[r]) out += "," + (r == 0 ? quoted(f) : f);
    out += "\n";
  }
  return out;
}

// A spreadsheet's export: a UTF-8 byte-order mark, CRLF endings, no newline after the last row.
inline std::string spreadsheet(const std::string& plain) {
  const auto rows = rows_of(plain);
  std::string out = "\xEF\xBB\xBF";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (r > 0) out += "\r\n";
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      if (c > 0) out += ',';
      out += rows[r][c];
    }
  }
  return out;
}

// Every field quoted, CRLF endings, blank lines between rows and at the end; with `note`, a first
// free-text column whose values hold commas, doubled quotes and a line break (a note typed by a person).
inline std::string quoted_everywhere(const std::string& plain, bool note) {
  const auto rows = rows_of(plain);
  std::string out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (note) out += (r == 0 ? quoted("note, free text") : quoted("take " + std::to_string(r) + ", \"steady\"\nhand")) + ",";
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      if (c > 0) out += ',';
      out += quoted(rows[r][c]);
    }
    out += r % 100 == 1 ? "\r\n\r\n" : "\r\n";
  }
  return out + "\n\n";
}

}  // namespace csv_dialects
