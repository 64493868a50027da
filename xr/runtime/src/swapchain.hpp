// OpenGL swapchains (XR_KHR_opengl_enable): three textures made in the app's current context (one for a
// static swapchain), handed out round-robin through acquire / wait / release.
#pragma once

#include <vector>

#include "objects.hpp"

namespace wedge::xr_replay {

// The formats offered, most preferred first: GL_SRGB8_ALPHA8, GL_RGBA8, GL_RGBA16F, GL_DEPTH_COMPONENT24,
// GL_DEPTH_COMPONENT32F.
const std::vector<int64_t>& swapchain_formats();

bool is_color_format(int64_t format);

// The pixels of image `image`, layer `array_index`, inside `rect` (in GL texel coordinates: row 0 at the
// bottom), as 8-bit RGBA with the top row first. Needs the session's context current; "" or the problem.
std::string read_image(const Session& s, const Swapchain& sc, uint32_t image, uint32_t array_index, const XrRect2Di& rect,
                       std::vector<uint8_t>& rgba);

}  // namespace wedge::xr_replay
