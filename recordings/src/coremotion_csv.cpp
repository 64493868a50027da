#include "wedge/recordings/coremotion_csv.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "wedge/error.hpp"

namespace wedge::recordings {
namespace {

// The fields of a line; a CRLF line ending (as the shipped traces have) is not part of the last field.
std::vector<std::string> split(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

std::vector<CoreMotionSample> read_coremotion_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open file");
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ": empty file (expected a CoreMotion CSV header row)");
  const std::vector<std::string> header = split(line);
  // Column index of each value read, in CoreMotionSample's order.
  const std::array<const char*, 10> names = {"timestamp",           "gravity.x",           "gravity.y",
                                             "gravity.z",           "userAcceleration.x",  "userAcceleration.y",
                                             "userAcceleration.z",  "rotationRate.x",      "rotationRate.y",
                                             "rotationRate.z"};
  std::array<std::size_t, 10> column{};
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::size_t c = 0;
    while (c < header.size() && header[c] != names[k]) ++c;
    if (c == header.size()) throw Error(path + ": line 1: no column '" + names[k] + "' in the header");
    column[k] = c;
  }
  std::vector<CoreMotionSample> samples;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> fields = split(line);
    if (fields.size() != header.size())
      throw Error(path + ": line " + std::to_string(number) + ": " + std::to_string(fields.size()) +
                  " fields, the header has " + std::to_string(header.size()));
    std::array<double, 10> v{};
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& text = fields[column[k]];
      char* end = nullptr;
      errno = 0;
      v[k] = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v[k]))
        throw Error(path + ": line " + std::to_string(number) + ": " + names[k] + " is not a finite number ('" +
                    text + "')");
    }
    CoreMotionSample s;
    s.time = v[0];
    s.gravity = {v[1], v[2], v[3]};
    s.user_acceleration = {v[4], v[5], v[6]};
    s.rotation_rate = {v[7], v[8], v[9]};
    if (!samples.empty() && s.time < samples.back().time)
      throw Error(path + ": line " + std::to_string(number) + ": timestamp goes backwards");
    samples.push_back(s);
  }
  if (samples.empty()) throw Error(path + ": no samples after the header");
  return samples;
}

}  // namespace wedge::recordings
