// Path syntax and the atom table (paths.hpp). The entry points xrStringToPath and xrPathToString are in
// actions.cpp, with the rest of the input API.
#include "paths.hpp"

namespace wedge::xr_replay {

bool is_path_name(std::string_view s) {
  bool only_dots = true;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    if (!ok) return false;
    only_dots = only_dots && c == '.';
  }
  return !s.empty() && !only_dots;
}

bool is_well_formed_path(std::string_view s) {
  if (s.size() < 2 || s.size() >= XR_MAX_PATH_LENGTH || s.front() != '/') return false;
  std::size_t start = 1;
  while (true) {
    const std::size_t slash = s.find('/', start);
    const std::string_view name = s.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (!is_path_name(name)) return false;  // also catches "//" and a trailing '/'
    if (slash == std::string_view::npos) return true;
    start = slash + 1;
  }
}

XrPath PathTable::intern(std::string_view s) {
  const auto it = ids_.find(s);
  if (it != ids_.end()) return it->second;
  strings_.emplace_back(s);
  const XrPath id = XrPath(strings_.size());
  ids_.emplace(std::string(s), id);
  return id;
}

const std::string* PathTable::find(XrPath p) const {
  if (p == XR_NULL_PATH || p > strings_.size()) return nullptr;
  return &strings_[std::size_t(p - 1)];
}

XrPath PathTable::lookup(std::string_view s) const {
  const auto it = ids_.find(s);
  return it == ids_.end() ? XR_NULL_PATH : it->second;
}

}  // namespace wedge::xr_replay
