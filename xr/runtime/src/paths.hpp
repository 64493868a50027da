// Semantic paths: the string <-> XrPath atom table of an instance, and the spec's syntax rules
// ("Well-Formed Path Strings"). Atoms are handed out in order of first use, from 1, so they are the same
// from run to run.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "xr_platform.hpp"

namespace wedge::xr_replay {

// A path name string: one or more of a-z, 0-9, '-', '_', '.', not dots only. Action and action set names
// are path name strings too.
bool is_path_name(std::string_view s);
// '/' name ('/' name)*, shorter than XR_MAX_PATH_LENGTH.
bool is_well_formed_path(std::string_view s);

class PathTable {
 public:
  XrPath intern(std::string_view s);                 // s must be well formed
  const std::string* find(XrPath p) const;           // null for XR_NULL_PATH or an atom never handed out
  XrPath lookup(std::string_view s) const;           // XR_NULL_PATH when s was never interned
  bool is_valid(XrPath p) const { return find(p) != nullptr; }

 private:
  std::vector<std::string> strings_;                 // atom i + 1
  std::map<std::string, XrPath, std::less<>> ids_;
};

}  // namespace wedge::xr_replay
