// The scene library's errors. A SceneError is what a caller shows: one line that starts with the file's
// name and, for a problem inside the document, the JSON path ("scene.json: bodies[2].shape.half_extents:
// expected 4 numbers, got 3"). A JsonError is a problem at a place in a document, not yet tied to a file:
// the readers throw it and the loader turns it into a SceneError (with_file_context, scene.hpp).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace wedge::scenes {

class SceneError : public std::runtime_error {
 public:
  explicit SceneError(const std::string& what) : std::runtime_error(what) {}
};

// path: "bodies[2].shape.half_extents"; what: "expected 4 numbers, got 3".
class JsonError : public std::runtime_error {
 public:
  JsonError(std::string path, const std::string& what)
      : std::runtime_error(path.empty() ? what : path + ": " + what), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace wedge::scenes
