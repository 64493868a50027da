// JSON output: GA values and matrices as plain arrays, and output that appears whole or not at all.
//
// Numbers are written by nlohmann's dump(), which prints the shortest text that reads back to the same
// double (round-trip exact). Vectors, bivectors and rotors are flat arrays in their component order;
// matrices are arrays of rows. Objects keep their keys in the order they were added.
#pragma once

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "wedge/ga/types.hpp"

namespace wedge::cli {

// Output objects keep their keys in insertion order ("step" first), unlike the sorted input Json.
using OutJson = nlohmann::ordered_json;

template <class Derived>
OutJson to_json_array(const Eigen::MatrixBase<Derived>& v) {
  OutJson a = OutJson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(double(v(i)));
  return a;
}

template <class Derived>
OutJson to_json_rows(const Eigen::MatrixBase<Derived>& m) {
  OutJson rows = OutJson::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) rows.push_back(to_json_array(m.row(r)));
  return rows;
}

template <int N>
OutJson to_json(const Vec<N>& v) {
  return to_json_array(v);
}
template <int N>
OutJson to_json(const Bivector<N>& b) {
  return to_json_array(b.c);
}
template <int N>
OutJson to_json(const Rotor<N>& r) {
  return to_json_array(r.c);
}

// The path of the first number in the document that is not finite ("energy", "bodies[1].velocity[0]"),
// or "" if all are (nlohmann would print NaN and inf as null).
std::string first_non_finite(const OutJson& j, const std::string& path = "");
inline bool all_finite(const OutJson& j) { return first_non_finite(j).empty(); }

// Output that appears whole or not at all. For a file, lines go to a temporary file next to it that is
// renamed into place by commit(); for stdout, to an anonymous temporary file copied to stdout by
// commit(). If the sink is destroyed without commit() (an error), nothing appears.
class OutputSink {
 public:
  // `path` empty: stdout. Throws Failure if the temporary file cannot be made.
  explicit OutputSink(const std::string& path);
  ~OutputSink();
  OutputSink(const OutputSink&) = delete;
  OutputSink& operator=(const OutputSink&) = delete;

  void write_line(const std::string& line);  // throws Failure on a write error
  void commit();                             // rename into place, or copy to stdout

 private:
  std::string path_, temp_path_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace wedge::cli
