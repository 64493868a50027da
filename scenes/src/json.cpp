// Strict JSON reading with paths; see wedge/scenes/json.hpp.
#include "wedge/scenes/json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "wedge/error.hpp"
#include "wedge/fp_env.hpp"

namespace wedge::scenes {

namespace {

// nlohmann's messages start with "[json.exception.parse_error.101] "; the tag means nothing to a user.
std::string strip_exception_tag(const std::string& what) {
  if (!what.empty() && what[0] == '[') {
    const std::size_t end = what.find("] ");
    if (end != std::string::npos) return what.substr(end + 2);
  }
  return what;
}

std::string plural(std::size_t n, const char* what) {
  std::string w = what;
  if (n == 1 && !w.empty() && w.back() == 's') w.pop_back();
  return std::to_string(n) + " " + w;
}

}  // namespace

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string child_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? printable(key) : parent + "." + printable(key);
}

std::string index_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

namespace {

// Refuses a key that appears twice in one object (nlohmann keeps the last one silently), naming the
// object's path. Tracks the path through the parser's events: objects and arrays open and close, keys
// name the next value, and each finished value advances the index of the array around it.
class DuplicateKeyCheck {
 public:
  bool operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start: open(false); break;
      case Json::parse_event_t::array_start: open(true); break;
      case Json::parse_event_t::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw JsonError(path(), "duplicate key '" + printable(f.key) + "' (each key may appear once in an object)");
        break;
      }
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        frames_.pop_back();
        finished_value();
        break;
      case Json::parse_event_t::value: finished_value(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  void open(bool array) { frames_.push_back(Frame{array, 0, {}, {}}); }
  void finished_value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  // The path of the innermost open object, as the loader's messages write it.
  std::string path() const {
    std::string p;
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i)
      p = frames_[i].array ? index_path(p, frames_[i].index) : child_path(p, frames_[i].key);
    return p;
  }
  std::vector<Frame> frames_;
};

}  // namespace

Json read_json_file(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw SceneError(file + ": is a folder, not a JSON file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file + ": cannot open file (" + std::strerror(errno) + ")");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(file + ": cannot read file");
  try {
    const ExpectedFpExceptions quiet;  // 1e400 overflows while parsed: reported below
    return Json::parse(text.str(), DuplicateKeyCheck{});
  } catch (const JsonError& e) {
    throw SceneError(file + ": " + (e.path().empty() ? std::string("top level: ") : std::string()) + e.what());
  } catch (const Json::parse_error& e) {
    throw SceneError(file + ": malformed JSON: " + strip_exception_tag(e.what()));
  } catch (const Json::exception& e) {  // e.g. number overflow: "1e400"
    throw SceneError(file + ": malformed JSON: " + strip_exception_tag(e.what()));
  }
}

void Node::fail(const std::string& what) const { throw JsonError(path_, what); }

std::string Node::describe_type() const {
  switch (value_->type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::object: return "an object";
    case Json::value_t::array: return "an array";
    case Json::value_t::string: return "a string";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return "a number";
    default: return "an unsupported value";
  }
}

double Node::number() const {
  if (!value_->is_number()) fail("expected a number, got " + describe_type());
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  return v;
}

std::int64_t Node::integer() const {
  if (value_->is_number_integer()) {
    if (value_->is_number_unsigned() &&
        value_->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
      fail("integer out of range");
    return value_->get<std::int64_t>();
  }
  if (value_->is_number_float()) {
    const double v = value_->get<double>();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9.0e15) return std::int64_t(v);
    fail("expected an integer, got " + value_->dump());
  }
  fail("expected an integer, got " + describe_type());
}

bool Node::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + describe_type());
  return value_->get<bool>();
}

std::string Node::string() const {
  if (!value_->is_string()) fail("expected a string, got " + describe_type());
  return value_->get<std::string>();
}

std::vector<Node> Node::array() const {
  if (!value_->is_array()) fail("expected an array, got " + describe_type());
  std::vector<Node> out;
  out.reserve(value_->size());
  for (std::size_t i = 0; i < value_->size(); ++i) out.emplace_back((*value_)[i], index_path(path_, i));
  return out;
}

std::vector<Node> Node::array(std::size_t expected, const char* what) const {
  if (!value_->is_array()) fail("expected an array of " + plural(expected, what) + ", got " + describe_type());
  if (value_->size() != expected)
    fail("expected " + plural(expected, what) + ", got " + std::to_string(value_->size()));
  return array();
}

std::vector<double> Node::numbers() const {
  std::vector<double> out;
  for (const Node& e : array()) out.push_back(e.number());
  return out;
}

std::vector<double> Node::numbers(std::size_t expected) const {
  std::vector<double> out;
  for (const Node& e : array(expected, "numbers")) out.push_back(e.number());
  return out;
}

ObjectReader::ObjectReader(const Node& node) : node_(node) {
  if (!node.json().is_object()) node.fail("expected an object, got " + node.describe_type());
}

bool ObjectReader::has(const std::string& key) const { return node_.json().contains(key); }

std::optional<Node> ObjectReader::optional(const std::string& key) {
  if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.push_back(key);
  const auto it = node_.json().find(key);
  if (it == node_.json().end()) return std::nullopt;
  return Node(*it, child_path(node_.path(), key));
}

Node ObjectReader::required(const std::string& key) {
  std::optional<Node> n = optional(key);
  if (!n) node_.fail("missing key \"" + key + "\"");
  return *n;
}

double ObjectReader::number_or(const std::string& key, double fallback) {
  const std::optional<Node> n = optional(key);
  return n ? n->number() : fallback;
}

bool ObjectReader::boolean_or(const std::string& key, bool fallback) {
  const std::optional<Node> n = optional(key);
  return n ? n->boolean() : fallback;
}

void ObjectReader::finish() const {
  for (const auto& item : node_.json().items()) {
    if (std::find(asked_.begin(), asked_.end(), item.key()) != asked_.end()) continue;
    std::vector<std::string> allowed = asked_;
    std::sort(allowed.begin(), allowed.end());
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw JsonError(child_path(node_.path(), item.key()), "unknown key (allowed here: " + list + ")");
  }
}

}  // namespace wedge::scenes
