// OpenGL swapchains (swapchain.hpp): creation in the app's current context, the acquire / wait / release
// order checks, reading images back for frame capture.
#include "swapchain.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>

#include "api.hpp"
#include "registry.hpp"
#include "system.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

struct FormatInfo {
  int64_t internal_format;
  GLenum format, type;  // a pixel transfer pair glTexImage accepts for it
};
const FormatInfo kFormats[] = {
    {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE},
    {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE},
    {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT},
    {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT},
    {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT},
};

const FormatInfo* format_info(int64_t f) {
  for (const FormatInfo& i : kFormats)
    if (i.internal_format == f) return &i;
  return nullptr;
}

// Saves the GL state the runtime touches (the texture binding of `target` on the active unit, the pixel
// buffers, the pack layout) and puts it back on destruction, so the app's context is as it left it. In
// between, pixels are packed tightly into client memory.
class GlStateGuard {
 public:
  GlStateGuard(const GlFunctions& gl, GLenum target) : gl_(gl), target_(target) {
    gl.GetIntegerv(target == GL_TEXTURE_2D ? GL_TEXTURE_BINDING_2D : GL_TEXTURE_BINDING_2D_ARRAY, &texture_);
    gl.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
    for (std::size_t i = 0; i < kPack.size(); ++i) gl.GetIntegerv(kPack[i], &pack_[i]);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    for (std::size_t i = 0; i < kPack.size(); ++i) gl.PixelStorei(kPack[i], kPack[i] == GL_PACK_ALIGNMENT ? 1 : 0);
  }
  ~GlStateGuard() {
    gl_.BindTexture(target_, GLuint(texture_));
    gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_buffer_));
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer_));
    for (std::size_t i = 0; i < kPack.size(); ++i) gl_.PixelStorei(kPack[i], pack_[i]);
  }
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  static constexpr std::array<GLenum, 6> kPack = {GL_PACK_ALIGNMENT,   GL_PACK_ROW_LENGTH,   GL_PACK_SKIP_ROWS,
                                                  GL_PACK_SKIP_PIXELS, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_IMAGES};
  const GlFunctions& gl_;
  GLenum target_;
  GLint texture_ = 0, unpack_buffer_ = 0, pack_buffer_ = 0;
  std::array<GLint, 6> pack_{};
};

GLenum texture_target(const XrSwapchainCreateInfo& info) { return info.arraySize > 1 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D; }

// Makes the swapchain's textures: all mip levels and layers, no data. "" or the problem.
std::string make_textures(const GlFunctions& gl, Swapchain& sc, uint32_t count) {
  const XrSwapchainCreateInfo& info = sc.info;
  const FormatInfo& f = *format_info(info.format);
  const GLenum target = texture_target(info);
  GlStateGuard guard(gl, target);
  while (gl.GetError() != GL_NO_ERROR) {
  }  // the app's own pending errors are not ours
  sc.textures.assign(count, 0);
  gl.GenTextures(GLsizei(count), sc.textures.data());
  for (GLuint t : sc.textures) {
    gl.BindTexture(target, t);
    for (uint32_t level = 0; level < info.mipCount; ++level) {
      const GLsizei w = GLsizei(std::max(1u, info.width >> level)), h = GLsizei(std::max(1u, info.height >> level));
      if (target == GL_TEXTURE_2D)
        gl.TexImage2D(target, GLint(level), GLint(info.format), w, h, 0, f.format, f.type, nullptr);
      else
        gl.TexImage3D(target, GLint(level), GLint(info.format), w, h, GLsizei(info.arraySize), 0, f.format, f.type, nullptr);
    }
    gl.TexParameteri(target, GL_TEXTURE_MAX_LEVEL, GLint(info.mipCount - 1));
    gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, info.mipCount > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  const GLenum error = gl.GetError();
  if (error == GL_NO_ERROR) return "";
  gl.DeleteTextures(GLsizei(count), sc.textures.data());
  sc.textures.clear();
  char text[64];
  std::snprintf(text, sizeof(text), "glTexImage failed (GL error 0x%X)", unsigned(error));
  return text;
}

XrResult check_create_info(const XrSwapchainCreateInfo& info) {
  const XrSwapchainCreateFlags known = XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT | XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
  if ((info.createFlags & ~known) != 0) return XR_ERROR_VALIDATION_FAILURE;
  if (info.createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) return XR_ERROR_FEATURE_UNSUPPORTED;
  if (format_info(info.format) == nullptr) return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
  if (info.width == 0 || info.height == 0 || info.width > kMaxImageSize || info.height > kMaxImageSize ||
      info.arraySize == 0 || info.mipCount == 0 || info.sampleCount == 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info.faceCount == 6) return XR_ERROR_FEATURE_UNSUPPORTED;  // no cube swapchains
  if (info.faceCount != 1 || info.sampleCount > 1) return XR_ERROR_VALIDATION_FAILURE;
  if ((1u << (info.mipCount - 1)) > std::max(info.width, info.height)) return XR_ERROR_VALIDATION_FAILURE;
  return XR_SUCCESS;
}

XrResult create_swapchain(XrSession session, const XrSwapchainCreateInfo* info, XrSwapchain* out) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (s->headless) return XR_ERROR_VALIDATION_FAILURE;  // a headless session has nothing to show images on
  if (!has_type(info, XR_TYPE_SWAPCHAIN_CREATE_INFO) || out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_create_info(*info); r != XR_SUCCESS) return r;
  if (!s->gl.context_current()) {
    const std::string problem = load_current_gl(s->gl);
    if (!problem.empty()) {
      report("xrCreateSwapchain: " + problem);
      return XR_ERROR_RUNTIME_FAILURE;
    }
  }
  auto sc = std::make_unique<Swapchain>();
  sc->session = s;
  sc->info = *info;
  sc->info.next = nullptr;
  const uint32_t count = (info->createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) ? 1 : 3;
  const std::string problem = make_textures(s->gl, *sc, count);
  if (!problem.empty()) {
    report("xrCreateSwapchain: " + problem);
    return XR_ERROR_RUNTIME_FAILURE;
  }
  *out = handle_of<XrSwapchain>(add(std::move(sc))->id);
  return XR_SUCCESS;
}

}  // namespace

const std::vector<int64_t>& swapchain_formats() {
  static const std::vector<int64_t> formats = [] {
    std::vector<int64_t> v;
    for (const FormatInfo& f : kFormats) v.push_back(f.internal_format);
    return v;
  }();
  return formats;
}

bool is_color_format(int64_t format) {
  const FormatInfo* f = format_info(format);
  return f != nullptr && f->format == GL_RGBA;
}

std::string read_image(const Session& s, const Swapchain& sc, uint32_t image, uint32_t array_index, const XrRect2Di& rect,
                       std::vector<uint8_t>& rgba) {
  if (!s.gl.context_current()) return "no OpenGL context is current";
  const GlFunctions& gl = s.gl;
  const GLenum target = texture_target(sc.info);
  const std::size_t w = sc.info.width, h = sc.info.height, layer_bytes = w * h * 4;
  std::vector<uint8_t> all(layer_bytes * sc.info.arraySize);
  {
    GlStateGuard guard(gl, target);
    gl.BindTexture(target, sc.textures[image]);
    gl.GetTexImage(target, 0, GL_RGBA, GL_UNSIGNED_BYTE, all.data());
  }
  const std::size_t rw = std::size_t(rect.extent.width), rh = std::size_t(rect.extent.height);
  rgba.assign(rw * rh * 4, 0);
  const uint8_t* layer = all.data() + layer_bytes * array_index;
  for (std::size_t y = 0; y < rh; ++y) {
    const std::size_t gl_row = std::size_t(rect.offset.y) + rh - 1 - y;  // GL rows go bottom up
    std::memcpy(rgba.data() + y * rw * 4, layer + (gl_row * w + std::size_t(rect.offset.x)) * 4, rw * 4);
  }
  return "";
}

XrResult xrEnumerateSwapchainFormats(XrSession session, uint32_t capacity, uint32_t* count, int64_t* formats) {
  return guarded("xrEnumerateSwapchainFormats", [&]() -> XrResult {
    const Session* s = find(session);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    return two_call(capacity, count, formats, s->headless ? std::vector<int64_t>{} : swapchain_formats());
  });
}

XrResult xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* createInfo, XrSwapchain* swapchain) {
  return guarded("xrCreateSwapchain", [&] { return create_swapchain(session, createInfo, swapchain); });
}

XrResult xrDestroySwapchain(XrSwapchain swapchain) {
  return guarded("xrDestroySwapchain", [&]() -> XrResult {
    Swapchain* sc = find(swapchain);
    if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(sc);
    return XR_SUCCESS;
  });
}

XrResult xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t capacity, uint32_t* count,
                                    XrSwapchainImageBaseHeader* images) {
  return guarded("xrEnumerateSwapchainImages", [&]() -> XrResult {
    const Swapchain* sc = find(swapchain);
    if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto* gl_images = reinterpret_cast<XrSwapchainImageOpenGLKHR*>(images);
    return two_call_structs(capacity, count, gl_images, uint32_t(sc->textures.size()), XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR,
                            [&](uint32_t i, XrSwapchainImageOpenGLKHR& image) { image.image = sc->textures[i]; });
  });
}

XrResult xrAcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo* acquireInfo, uint32_t* index) {
  return guarded("xrAcquireSwapchainImage", [&]() -> XrResult {
    Swapchain* sc = find(swapchain);
    if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
    if ((acquireInfo != nullptr && acquireInfo->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) || index == nullptr)
      return XR_ERROR_VALIDATION_FAILURE;
    const bool is_static = (sc->info.createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) != 0;
    if ((is_static && sc->ever_acquired) || sc->acquired.size() == sc->textures.size()) return XR_ERROR_CALL_ORDER_INVALID;
    *index = sc->next_image;
    sc->acquired.push_back(sc->next_image);
    sc->next_image = (sc->next_image + 1) % uint32_t(sc->textures.size());
    sc->ever_acquired = true;
    return XR_SUCCESS;
  });
}

XrResult xrWaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo* waitInfo) {
  return guarded("xrWaitSwapchainImage", [&]() -> XrResult {
    Swapchain* sc = find(swapchain);
    if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(waitInfo, XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO)) return XR_ERROR_VALIDATION_FAILURE;
    if (sc->acquired.empty() || sc->waited) return XR_ERROR_CALL_ORDER_INVALID;
    sc->waited = true;  // images are ready at once: the app's GL commands are its own context's
    return XR_SUCCESS;
  });
}

XrResult xrReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo* releaseInfo) {
  return guarded("xrReleaseSwapchainImage", [&]() -> XrResult {
    Swapchain* sc = find(swapchain);
    if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (releaseInfo != nullptr && releaseInfo->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO)
      return XR_ERROR_VALIDATION_FAILURE;
    if (!sc->waited) return XR_ERROR_CALL_ORDER_INVALID;
    sc->last_released = int(sc->acquired.front());
    sc->acquired.pop_front();
    sc->waited = false;
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay
