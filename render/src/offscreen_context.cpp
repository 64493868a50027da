// OSMesa with a core-profile 3.3 context (Mesa's llvmpipe), drawing into OSMesa's own RGBA buffer (the
// default framebuffer), which read_rgba() hands back after glFinish.
#define GL_GLEXT_PROTOTYPES 1
#include "wedge/render/offscreen_context.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <string>

#include "wedge/error.hpp"

namespace wedge::render {

struct OffscreenContext::Impl {
  OSMesaContext ctx = nullptr;
  std::vector<std::uint8_t> buffer;
};

OffscreenContext::OffscreenContext(int width, int height)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error("offscreen context: size must be 1..16384 pixels each way (got " + std::to_string(width) + "x" +
                std::to_string(height) + ")");
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  impl_->ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (impl_->ctx == nullptr) throw Error("offscreen context: OSMesa could not create an OpenGL 3.3 core context");
  impl_->buffer.assign(std::size_t(width) * std::size_t(height) * 4, 0);
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (impl_->ctx != nullptr) OSMesaDestroyContext(impl_->ctx);
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->ctx, impl_->buffer.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw Error("offscreen context: OSMesaMakeCurrent failed");
  OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 of the buffer is the top of the image
}

std::vector<std::uint8_t> OffscreenContext::read_rgba() {
  glFinish();
  return impl_->buffer;
}

}  // namespace wedge::render
