// An offscreen OpenGL 3.3 core context through OSMesa (Mesa's software rasteriser): no display, no GPU.
// It owns the RGBA pixel buffer it renders into; read_rgba() returns the image top row first.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace wedge::render {

class OffscreenContext {
 public:
  // Creates the context and makes it current on this thread; throws wedge::Error on failure.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  void make_current();
  int width() const { return width_; }
  int height() const { return height_; }
  // Finishes rendering and returns width * height * 4 bytes, rows from the top.
  std::vector<std::uint8_t> read_rgba();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace wedge::render
