// Writing submitted frames out (WEDGE_XR_FRAMES=DIR): each eye's image as DIR/frame_NNNNNN_eye{0,1}.png
// (8-bit RGBA, top row first) and DIR/frame_NNNNNN.json with what the app submitted for it, so a test can
// project tracking-space points through exactly the views the app rendered:
//   {"frame": N, "display_time_ns": T, "t": S,
//    "space": {"type": "LOCAL", "located": true, "pose": {...}},   // the layer's space in tracking space at T
//    "eyes": [{"image": "frame_NNNNNN_eye0.png", "pose": {"position": [x,y,z], "orientation": [x,y,z,w]},
//              "fov": {"angle_left": l, "angle_right": r, "angle_up": u, "angle_down": d},
//              "image_rect": {"x":..,"y":..,"width":..,"height":..}, "swapchain_size": [w, h],
//              "format": 32856, "format_name": "GL_RGBA8", "array_index": 0}, ...]}
// The eye poses are in the layer's space, as submitted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pose.hpp"

namespace wedge::xr_replay {

struct CapturedEye {
  Pose pose;
  XrFovf fov{};
  XrRect2Di rect{};
  int64_t format = 0;
  uint32_t image_width = 0, image_height = 0, array_index = 0;
  std::vector<uint8_t> rgba;  // rect.extent.width x rect.extent.height, 4 bytes a pixel, top row first
};

struct CapturedFrame {
  uint64_t index = 0;  // counts the session's submitted frames (successful xrEndFrame calls with a projection layer)
  XrTime display_time = 0;
  std::string space_type;  // "VIEW", "LOCAL", "STAGE" or "ACTION"
  bool space_located = false;
  Pose space_pose;
  std::vector<CapturedEye> eyes;
};

// Returns "" on success, else the problem (the files are then incomplete).
std::string write_captured_frame(const std::string& dir, const CapturedFrame& frame);

// GL_RGBA8 -> "GL_RGBA8", for the formats the runtime offers.
const char* gl_format_name(int64_t format);

}  // namespace wedge::xr_replay
