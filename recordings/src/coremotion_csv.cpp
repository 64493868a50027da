#include "wedge/recordings/coremotion_csv.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "csv_table.hpp"
#include "wedge/parse_number.hpp"
#include "wedge/error.hpp"

namespace wedge::recordings {

std::vector<CoreMotionSample> read_coremotion_csv(const std::string& path) {
  const std::vector<CsvRecord> records = read_csv(path);
  auto fail = [&](int line, const std::string& problem) {
    throw Error(path + ":" + std::to_string(line) + ": " + problem);
  };
  if (records.empty()) throw Error(path + ": empty file (expected a CoreMotion CSV header row)");
  const std::vector<std::string>& header = records.front().fields;
  // Column index of each value read, in CoreMotionSample's order.
  const std::array<const char*, 10> names = {"timestamp",           "gravity.x",           "gravity.y",
                                             "gravity.z",           "userAcceleration.x",  "userAcceleration.y",
                                             "userAcceleration.z",  "rotationRate.x",      "rotationRate.y",
                                             "rotationRate.z"};
  std::array<std::size_t, 10> column{};
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::size_t c = 0;
    while (c < header.size() && header[c] != names[k]) ++c;
    if (c == header.size()) fail(records.front().line, std::string("no column '") + names[k] + "' in the header");
    column[k] = c;
  }
  std::vector<CoreMotionSample> samples;
  for (std::size_t r = 1; r < records.size(); ++r) {
    const int number = records[r].line;
    const std::vector<std::string>& fields = records[r].fields;
    if (fields.size() != header.size())
      fail(number, std::to_string(fields.size()) + " fields, the header has " + std::to_string(header.size()));
    std::array<double, 10> v{};
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& text = fields[column[k]];
      if (!parse_finite(text, v[k]))
        fail(number, std::string(names[k]) + " is not a finite number ('" + printable(text) + "')");
    }
    CoreMotionSample s;
    s.time = v[0];
    s.gravity = {v[1], v[2], v[3]};
    s.user_acceleration = {v[4], v[5], v[6]};
    s.rotation_rate = {v[7], v[8], v[9]};
    if (!samples.empty() && s.time < samples.back().time) fail(number, "timestamp goes backwards");
    samples.push_back(s);
  }
  if (samples.empty()) throw Error(path + ": no samples after the header");
  return samples;
}

}  // namespace wedge::recordings
