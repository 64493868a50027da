#include "wedge/render/png.hpp"

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include "wedge/error.hpp"

namespace wedge::render {

void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4)
    throw Error("write_png: the pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height));
  const std::string part = path + ".part";
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGBA;
  image.flags = PNG_IMAGE_FLAG_FAST;  // frames of a run: speed over size (several times faster to write)
  std::error_code ec;
  if (!png_image_write_to_file(&image, part.c_str(), 0, rgba.data(), width * 4, nullptr)) {
    const std::string why = image.message;
    png_image_free(&image);
    std::filesystem::remove(part, ec);
    throw Error(path + ": cannot write PNG (" + why + ")");
  }
  std::filesystem::rename(part, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(part, ignored);
    throw Error(path + ": cannot write PNG (" + ec.message() + ")");
  }
}

std::vector<std::uint8_t> downscale_rgba(const std::vector<std::uint8_t>& rgba, int width, int height, int out_width,
                                         int out_height) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4 || out_width < 1 ||
      out_height < 1 || out_width > width || out_height > height)
    throw Error("downscale_rgba: bad sizes " + std::to_string(width) + "x" + std::to_string(height) + " -> " +
                std::to_string(out_width) + "x" + std::to_string(out_height));
  std::vector<std::uint8_t> out(std::size_t(out_width) * std::size_t(out_height) * 4);
  for (int oy = 0; oy < out_height; ++oy) {
    const int y0 = int(std::int64_t(oy) * height / out_height), y1 = int(std::int64_t(oy + 1) * height / out_height);
    for (int ox = 0; ox < out_width; ++ox) {
      const int x0 = int(std::int64_t(ox) * width / out_width), x1 = int(std::int64_t(ox + 1) * width / out_width);
      std::uint64_t sum[4] = {0, 0, 0, 0};
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
          for (int c = 0; c < 4; ++c)
            sum[c] += rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4 + std::size_t(c)];
      const std::uint64_t count = std::uint64_t(y1 - y0) * std::uint64_t(x1 - x0);
      for (int c = 0; c < 4; ++c)
        out[(std::size_t(oy) * std::size_t(out_width) + std::size_t(ox)) * 4 + std::size_t(c)] =
            std::uint8_t((sum[c] + count / 2) / count);
    }
  }
  return out;
}

namespace {

// 5x7 glyphs, one byte per row, bit 4 the leftmost pixel.
struct Glyph {
  char c;
  std::uint8_t rows[7];
};
constexpr Glyph kGlyphs[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}}, {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
};

const Glyph* find_glyph(char c) {
  for (const Glyph& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;
}

}  // namespace

ContactSheet::ContactSheet(int tiles, int columns, int tile_width, int tile_height)
    : tiles_(tiles), columns_(columns), tile_width_(tile_width), tile_height_(tile_height) {
  if (tiles < 1 || columns < 1 || tile_width < 1 || tile_height < 1)
    throw Error("ContactSheet: tiles, columns and the tile size must be positive");
  const int cols = std::min(columns, tiles), rows = (tiles + columns - 1) / columns;
  width_ = kBorder + cols * (tile_width + kBorder);
  height_ = kBorder + rows * (tile_height + kBorder);
  rgba_.assign(std::size_t(width_) * std::size_t(height_) * 4, 0);
  for (std::size_t i = 0; i < rgba_.size(); i += 4) rgba_[i] = rgba_[i + 1] = rgba_[i + 2] = 40, rgba_[i + 3] = 255;
}

void ContactSheet::place(int i, const std::vector<std::uint8_t>& rgba, int width, int height,
                         const std::string& label) {
  if (i < 0 || i >= tiles_) throw Error("ContactSheet: tile " + std::to_string(i) + " out of range");
  const std::vector<std::uint8_t> tile = downscale_rgba(rgba, width, height, tile_width_, tile_height_);
  const int x0 = tile_x(i), y0 = tile_y(i);
  for (int y = 0; y < tile_height_; ++y)
    std::copy_n(tile.begin() + std::ptrdiff_t(std::size_t(y) * std::size_t(tile_width_) * 4),
                std::size_t(tile_width_) * 4,
                rgba_.begin() + std::ptrdiff_t((std::size_t(y0 + y) * std::size_t(width_) + std::size_t(x0)) * 4));
  if (label.empty()) return;
  // The label: glyphs 6 px apart with a 3-px dark margin, clipped to the tile.
  auto put = [&](int x, int y, std::uint8_t v) {
    if (x < 0 || y < 0 || x >= tile_width_ || y >= tile_height_) return;
    std::uint8_t* p = &rgba_[(std::size_t(y0 + y) * std::size_t(width_) + std::size_t(x0 + x)) * 4];
    p[0] = p[1] = p[2] = v;
    p[3] = 255;
  };
  const int box_w = 6 * int(label.size()) + 5, box_h = 13;
  for (int y = 0; y < box_h; ++y)
    for (int x = 0; x < box_w; ++x) put(x, y, 30);
  for (std::size_t k = 0; k < label.size(); ++k)
    if (const Glyph* g = find_glyph(label[k]))
      for (int r = 0; r < 7; ++r)
        for (int b = 0; b < 5; ++b)
          if (g->rows[r] & (0x10 >> b)) put(3 + 6 * int(k) + b, 3 + r, 255);
}

}  // namespace wedge::render
