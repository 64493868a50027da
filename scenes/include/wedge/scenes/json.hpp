// Strict reading of JSON input: every value is read through a Node that knows its path in the
// document ("bodies[2].shape.radius"), so every error names the place it was found. Objects are read
// through an ObjectReader that remembers which keys were used; finish() rejects any key left over.
// Numbers must be finite; vectors must have exactly the expected length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "wedge/scenes/error.hpp"
#include "wedge/ga/types.hpp"

namespace wedge::scenes {

using Json = nlohmann::json;

// Reads and parses a whole JSON file; throws SceneError("FILE: ...") if it cannot be read or parsed.
Json read_json_file(const std::string& file);

class Node {
 public:
  Node(const Json& value, std::string path) : value_(&value), path_(std::move(path)) {}

  const Json& json() const { return *value_; }
  const std::string& path() const { return path_; }
  // Throws JsonError at this node's path.
  [[noreturn]] void fail(const std::string& what) const;

  double number() const;          // a finite number
  std::int64_t integer() const;   // an integer-valued number (1 and 1.0 both are)
  bool boolean() const;
  std::string string() const;
  std::vector<Node> array() const;  // the elements of an array, with their paths
  std::vector<Node> array(std::size_t expected, const char* what = "elements") const;
  std::vector<double> numbers() const;  // an array of finite numbers, of any length
  std::vector<double> numbers(std::size_t expected) const;

  template <int N>
  Vec<N> vec() const {
    const std::vector<double> v = numbers(N);
    Vec<N> out;
    for (int i = 0; i < N; ++i) out[i] = v[i];
    return out;
  }
  // Any fixed-size coefficient type (Bivector, Rotor): `Size` numbers into .c.
  template <class T>
  T coeffs() const {
    const std::vector<double> v = numbers(T::size());
    T out;
    for (int i = 0; i < T::size(); ++i) out.c[i] = v[i];
    return out;
  }

  std::string describe_type() const;  // "a string", "an array", .. for messages

 private:
  const Json* value_;
  std::string path_;
};

class ObjectReader {
 public:
  explicit ObjectReader(const Node& node);

  // The value of `key` if present (and marks it used).
  std::optional<Node> optional(const std::string& key);
  // The value of `key`; throws "missing key" if absent.
  Node required(const std::string& key);
  bool has(const std::string& key) const;
  // Throws for the first key (in alphabetical order) that was never asked for, listing the keys that
  // were asked for (present or not) as the allowed ones.
  void finish() const;
  const Node& node() const { return node_; }

  double number_or(const std::string& key, double fallback);
  bool boolean_or(const std::string& key, bool fallback);

 private:
  Node node_;
  std::vector<std::string> asked_;
};

// A number for messages: up to 6 significant digits ("0.01", "1e-07").
std::string format_number(double v);

std::string child_path(const std::string& parent, const std::string& key);
std::string index_path(const std::string& parent, std::size_t index);

}  // namespace wedge::scenes
