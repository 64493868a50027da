// PNG output (libpng): 8-bit RGBA, rows from the top.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace wedge::render {

// Writes the image to `path`; throws wedge::Error if the file cannot be written.
void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height);

}  // namespace wedge::render
