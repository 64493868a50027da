// Reading a PNG a test's program wrote (libpng's simplified API) and finding the pixels of one colour in
// it: how many, their centroid and their bounding box. Shared by the viewer's and the OpenXR app's tests.
#pragma once

#include <png.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <vector>

// An image's pixels, RGB rows top down.
struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const { return &rgb[3 * (std::size_t(y) * width + x)]; }
};
inline Image load(const std::filesystem::path& file) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&img, file.string().c_str()) != 0);
  img.format = PNG_FORMAT_RGB;
  Image out;
  out.rgb.resize(PNG_IMAGE_SIZE(img));
  REQUIRE(png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr) != 0);
  out.width = img.width;
  out.height = img.height;
  return out;
}

// Where the pixels that pass `is` are, in the box [x0, x1) x [y0, y1) (clipped): their count, centroid and
// bounding box (px, from the top left).
struct Blob {
  long count = 0;
  double x = 0, y = 0;
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
};
template <typename Pred>
Blob find(const Image& im, Pred is, int x0 = 0, int y0 = 0, int x1 = 1 << 20, int y1 = 1 << 20) {
  Blob b;
  for (std::uint32_t y = std::uint32_t(std::max(y0, 0)); y < std::min(im.height, std::uint32_t(y1)); ++y)
    for (std::uint32_t x = std::uint32_t(std::max(x0, 0)); x < std::min(im.width, std::uint32_t(x1)); ++x)
      if (is(im.at(x, y))) {
        ++b.count, b.x += x, b.y += y;
        b.min_x = std::min(b.min_x, double(x)), b.max_x = std::max(b.max_x, double(x));
        b.min_y = std::min(b.min_y, double(y)), b.max_y = std::max(b.max_y, double(y));
      }
  if (b.count > 0) b.x /= double(b.count), b.y /= double(b.count);
  return b;
}
// A lit body of one pure colour: that channel dominates.
inline auto pure(int c) {
  return [c](const std::uint8_t* p) { return p[c] > 2 * p[(c + 1) % 3] + 30 && p[c] > 2 * p[(c + 2) % 3] + 30; };
}
