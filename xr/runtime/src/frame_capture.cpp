// PNG and JSON sidecar output of submitted frames (frame_capture.hpp).
#include "frame_capture.hpp"

#include <png.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "clock.hpp"
#include "decimal.hpp"

namespace wedge::xr_replay {

namespace {

using nlohmann::ordered_json;

std::string frame_stem(const std::string& dir, uint64_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%06llu", static_cast<unsigned long long>(index));
  return dir + "/" + name;
}

// 8-bit RGBA, rows top first. Returns "" or the problem.
std::string write_png(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return path + ": cannot create";
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info != nullptr ? &info : nullptr);
    std::fclose(f);
    return path + ": libpng could not write it";
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (uint32_t y = 0; y < height; ++y) png_write_row(png, rgba.data() + std::size_t(y) * width * 4);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(f) == 0 ? "" : path + ": write failed";
}

ordered_json pose_json(const Pose& p) {
  const XrPosef x = to_xr(p);
  return {{"position", {float_as_decimal(x.position.x), float_as_decimal(x.position.y), float_as_decimal(x.position.z)}},
          {"orientation",
           {float_as_decimal(x.orientation.x), float_as_decimal(x.orientation.y), float_as_decimal(x.orientation.z),
            float_as_decimal(x.orientation.w)}}};
}

}  // namespace

const char* gl_format_name(int64_t format) {
  switch (format) {
    case 0x8C43: return "GL_SRGB8_ALPHA8";
    case 0x8058: return "GL_RGBA8";
    case 0x8059: return "GL_RGB10_A2";
    case 0x881A: return "GL_RGBA16F";
    case 0x81A6: return "GL_DEPTH_COMPONENT24";
    case 0x8CAC: return "GL_DEPTH_COMPONENT32F";
    case 0x88F0: return "GL_DEPTH24_STENCIL8";
    default: return "unknown";
  }
}

std::string write_captured_frame(const std::string& dir, const CapturedFrame& frame) {
  const std::string stem = frame_stem(dir, frame.index);
  ordered_json eyes = ordered_json::array();
  for (std::size_t i = 0; i < frame.eyes.size(); ++i) {
    const CapturedEye& e = frame.eyes[i];
    const std::string image = stem + "_eye" + std::to_string(i) + ".png";
    const std::string problem = write_png(image, uint32_t(e.rect.extent.width), uint32_t(e.rect.extent.height), e.rgba);
    if (!problem.empty()) return problem;
    eyes.push_back({{"image", image.substr(dir.size() + 1)},
                    {"pose", pose_json(e.pose)},
                    {"fov",
                     {{"angle_left", float_as_decimal(e.fov.angleLeft)},
                      {"angle_right", float_as_decimal(e.fov.angleRight)},
                      {"angle_up", float_as_decimal(e.fov.angleUp)},
                      {"angle_down", float_as_decimal(e.fov.angleDown)}}},
                    {"image_rect",
                     {{"x", e.rect.offset.x}, {"y", e.rect.offset.y}, {"width", e.rect.extent.width},
                      {"height", e.rect.extent.height}}},
                    {"swapchain_size", {e.image_width, e.image_height}},
                    {"format", e.format},
                    {"format_name", gl_format_name(e.format)},
                    {"array_index", e.array_index}});
  }
  ordered_json space = {{"type", frame.space_type}, {"located", frame.space_located}};
  if (frame.space_located) space["pose"] = pose_json(frame.space_pose);
  const ordered_json doc = {{"frame", frame.index},
                            {"display_time_ns", frame.display_time},
                            {"t", xr_time_to_recording_seconds(frame.display_time)},
                            {"space", space},
                            {"eyes", eyes}};
  std::ofstream out(stem + ".json");
  out << doc.dump(1) << '\n';
  out.close();
  return out ? "" : stem + ".json: write failed";
}

}  // namespace wedge::xr_replay
