#include "wedge/render/png.hpp"

#include <png.h>

#include <cstdio>
#include <memory>

#include "wedge/error.hpp"

namespace wedge::render {

void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height) {
  if (width < 1 || height < 1 || rgba.size() != std::size_t(width) * std::size_t(height) * 4)
    throw Error("write_png: the pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height));
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGBA;
  image.flags = PNG_IMAGE_FLAG_FAST;  // frames of a run: speed over size (several times faster to write)
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgba.data(), width * 4, nullptr)) {
    const std::string why = image.message;
    png_image_free(&image);
    throw Error(path + ": cannot write PNG (" + why + ")");
  }
}

}  // namespace wedge::render
