// PNG output (libpng): 8-bit RGBA, rows from the top, and contact sheets (a grid of downscaled pictures
// in one PNG, for looking at a whole run at a glance).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace wedge::render {

// Writes the image to `path` atomically: into `path`.part, then renamed over `path`, so a reader never
// sees a partial file and a failed write leaves nothing behind. Throws wedge::Error if it cannot.
void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height);

// A box-filtered (area average) copy of an RGBA image at a smaller size; every output pixel averages the
// input pixels whose index range it covers, in integers, so the result is exact and deterministic.
std::vector<std::uint8_t> downscale_rgba(const std::vector<std::uint8_t>& rgba, int width, int height, int out_width,
                                         int out_height);

// A grid of `tiles` pictures, `columns` wide, each tile_width x tile_height, with a 4-pixel dark border
// around and between them. Unplaced tiles stay dark.
class ContactSheet {
 public:
  ContactSheet(int tiles, int columns, int tile_width, int tile_height);
  int width() const { return width_; }
  int height() const { return height_; }
  int tile_width() const { return tile_width_; }
  int tile_height() const { return tile_height_; }
  static constexpr int kBorder = 4;  // px
  // Top-left pixel of tile i (row-major).
  int tile_x(int i) const { return kBorder + (i % columns_) * (tile_width_ + kBorder); }
  int tile_y(int i) const { return kBorder + (i / columns_) * (tile_height_ + kBorder); }

  // Downscales the picture into tile i and writes `label` in its top-left corner: white 5x7-pixel
  // glyphs on a dark box. Only digits, '.', ' ', '=', 's' and 't' are drawn (others leave a gap).
  void place(int i, const std::vector<std::uint8_t>& rgba, int width, int height, const std::string& label = "");
  const std::vector<std::uint8_t>& rgba() const { return rgba_; }

 private:
  int tiles_, columns_, tile_width_, tile_height_, width_, height_;
  std::vector<std::uint8_t> rgba_;
};

}  // namespace wedge::render
