// The frame loop on the deterministic clock (clock.hpp): xrWaitFrame never blocks and never reads the wall
// clock, frame n is displayed at kEpoch + round(n * 1e9 / 90). xrBeginFrame / xrEndFrame follow the spec's
// order rules, xrEndFrame checks the layers, and with WEDGE_XR_FRAMES the submitted eye images are written
// out (frame_capture.hpp). A headless session has no frames to show: its xrWaitFrame paces the app (with
// shouldRender false) and its xrBeginFrame / xrEndFrame answer XR_ERROR_VALIDATION_FAILURE.
#include "api.hpp"
#include "frame_capture.hpp"
#include "registry.hpp"
#include "session_state.hpp"
#include "spaces.hpp"
#include "swapchain.hpp"
#include "system.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

// A sub-image: a live swapchain of this session, released at least once and not held by the app, a layer
// index it has, and a rectangle inside it.
XrResult check_sub_image(const Session& s, const XrSwapchainSubImage& sub, const Swapchain*& out) {
  const Swapchain* sc = find(sub.swapchain);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (sc->session != &s) return XR_ERROR_VALIDATION_FAILURE;
  if (sc->last_released < 0 || !sc->acquired.empty()) return XR_ERROR_LAYER_INVALID;
  if (sub.imageArrayIndex >= sc->info.arraySize) return XR_ERROR_VALIDATION_FAILURE;
  const XrRect2Di& r = sub.imageRect;
  if (r.offset.x < 0 || r.offset.y < 0 || r.extent.width <= 0 || r.extent.height <= 0 ||
      int64_t(r.offset.x) + r.extent.width > int64_t(sc->info.width) ||
      int64_t(r.offset.y) + r.extent.height > int64_t(sc->info.height))
    return XR_ERROR_SWAPCHAIN_RECT_INVALID;
  out = sc;
  return XR_SUCCESS;
}

XrResult check_space(const Session& s, XrSpace space) {
  const Space* sp = find(space);
  if (sp == nullptr) return XR_ERROR_HANDLE_INVALID;
  return sp->session == &s ? XR_SUCCESS : XR_ERROR_VALIDATION_FAILURE;
}

XrResult check_projection(const Session& s, const XrCompositionLayerProjection& p) {
  if (const XrResult r = check_space(s, p.space); r != XR_SUCCESS) return r;
  if (p.viewCount != kViewCount || p.views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < p.viewCount; ++i) {
    const XrCompositionLayerProjectionView& v = p.views[i];
    if (v.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
    if (!is_valid_pose(v.pose)) return XR_ERROR_POSE_INVALID;
    const Swapchain* sc = nullptr;
    if (const XrResult r = check_sub_image(s, v.subImage, sc); r != XR_SUCCESS) return r;
  }
  return XR_SUCCESS;
}

XrResult check_layers(const Session& s, const XrFrameEndInfo& info) {
  if (info.layerCount > kMaxLayers) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
  if (info.layerCount > 0 && info.layers == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < info.layerCount; ++i) {
    const XrCompositionLayerBaseHeader* l = info.layers[i];
    if (l == nullptr) return XR_ERROR_LAYER_INVALID;
    XrResult r = XR_ERROR_LAYER_INVALID;  // a layer type the runtime does not have
    if (l->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
      r = check_projection(s, *reinterpret_cast<const XrCompositionLayerProjection*>(l));
    } else if (l->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {
      const auto& q = *reinterpret_cast<const XrCompositionLayerQuad*>(l);
      const Swapchain* sc = nullptr;
      r = check_space(s, q.space);
      if (r == XR_SUCCESS) r = is_valid_pose(q.pose) ? check_sub_image(s, q.subImage, sc) : XR_ERROR_POSE_INVALID;
    }
    if (r != XR_SUCCESS) return r;
  }
  return XR_SUCCESS;
}

// Writes the first projection layer of a submitted frame (WEDGE_XR_FRAMES).
void capture(const Session& s, const XrFrameEndInfo& info, uint64_t index) {
  const XrCompositionLayerProjection* p = nullptr;
  for (uint32_t i = 0; i < info.layerCount && p == nullptr; ++i)
    if (info.layers[i]->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION)
      p = reinterpret_cast<const XrCompositionLayerProjection*>(info.layers[i]);
  if (p == nullptr) return;
  CapturedFrame frame;
  frame.index = index;
  frame.display_time = info.displayTime;
  const Space& space = *find(p->space);
  frame.space_type = space_type_name(space);
  const Located at = locate(space, info.displayTime);
  frame.space_located = at.valid;
  frame.space_pose = at.pose;
  for (uint32_t i = 0; i < p->viewCount; ++i) {
    const XrCompositionLayerProjectionView& v = p->views[i];
    const Swapchain& sc = *find(v.subImage.swapchain);
    CapturedEye eye;
    eye.pose = from_xr(v.pose);
    eye.fov = v.fov;
    eye.rect = v.subImage.imageRect;
    eye.format = sc.info.format;
    eye.image_width = sc.info.width;
    eye.image_height = sc.info.height;
    eye.array_index = v.subImage.imageArrayIndex;
    std::string problem = is_color_format(sc.info.format) ? "" : "a depth swapchain has no image to write";
    if (problem.empty())
      problem = read_image(s, sc, uint32_t(sc.last_released), v.subImage.imageArrayIndex, v.subImage.imageRect, eye.rgba);
    if (!problem.empty()) {
      report("WEDGE_XR_FRAMES: frame " + std::to_string(index) + ": " + problem);
      return;
    }
    frame.eyes.push_back(std::move(eye));
  }
  const std::string problem = write_captured_frame(s.instance->config.frames_dir, frame);
  if (!problem.empty()) report("WEDGE_XR_FRAMES: " + problem);
}

XrResult wait_frame(XrSession session, const XrFrameWaitInfo* waitInfo, XrFrameState* state) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if ((waitInfo != nullptr && waitInfo->type != XR_TYPE_FRAME_WAIT_INFO) || !has_type(state, XR_TYPE_FRAME_STATE))
    return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  // A second wait without a begin would block on a real runtime until the first frame began; here the
  // newer frame simply replaces the older one.
  s->now = frame_display_time(s->frames_waited++);
  s->frame_waited = true;
  state->predictedDisplayTime = s->instance->config.zero_display_time ? 0 : s->now;
  state->predictedDisplayPeriod = kFramePeriod;
  state->shouldRender = !s->headless && (s->state == XR_SESSION_STATE_VISIBLE || s->state == XR_SESSION_STATE_FOCUSED)
                            ? XR_TRUE
                            : XR_FALSE;
  stop_at_recording_end(*s);
  return XR_SUCCESS;
}

XrResult begin_frame(XrSession session, const XrFrameBeginInfo* info) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info != nullptr && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->headless) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->frame_waited) return XR_ERROR_CALL_ORDER_INVALID;
  s->frame_waited = false;
  if (s->frame_begun) return XR_FRAME_DISCARDED;  // the frame begun before is dropped; this one is begun
  s->frame_begun = true;
  return XR_SUCCESS;
}

XrResult end_frame(XrSession session, const XrFrameEndInfo* info) {
  Session* s = find(session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!has_type(info, XR_TYPE_FRAME_END_INFO)) return XR_ERROR_VALIDATION_FAILURE;
  if (s->headless) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->frame_begun) return XR_ERROR_CALL_ORDER_INVALID;
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE)
    return info->environmentBlendMode == XR_ENVIRONMENT_BLEND_MODE_ADDITIVE ||
                   info->environmentBlendMode == XR_ENVIRONMENT_BLEND_MODE_ALPHA_BLEND
               ? XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED
               : XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_layers(*s, *info); r != XR_SUCCESS) return r;
  s->frame_begun = false;
  const uint64_t index = s->frames_submitted++;
  const Config& c = s->instance->config;
  if (!c.frames_dir.empty() && index % c.frames_every == 0) capture(*s, *info, index);
  return XR_SUCCESS;
}

}  // namespace

XrResult xrWaitFrame(XrSession session, const XrFrameWaitInfo* frameWaitInfo, XrFrameState* frameState) {
  return guarded("xrWaitFrame", [&] { return wait_frame(session, frameWaitInfo, frameState); });
}

XrResult xrBeginFrame(XrSession session, const XrFrameBeginInfo* frameBeginInfo) {
  return guarded("xrBeginFrame", [&] { return begin_frame(session, frameBeginInfo); });
}

XrResult xrEndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo) {
  return guarded("xrEndFrame", [&] { return end_frame(session, frameEndInfo); });
}

}  // namespace wedge::xr_replay
