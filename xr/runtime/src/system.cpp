// The one system: a head-mounted display with a stereo view configuration, an opaque blend mode and
// OpenGL 3.3 to 4.6. Its system id is kSystemId; every other id is XR_ERROR_SYSTEM_INVALID.
#include "api.hpp"
#include "registry.hpp"
#include "system.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

// Instance and system id checks shared by the system queries.
XrResult check_system(XrInstance instance, XrSystemId system, Instance*& in) {
  in = find(instance);
  if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
  return system == kSystemId ? XR_SUCCESS : XR_ERROR_SYSTEM_INVALID;
}

}  // namespace

XrResult check_view_configuration(XrViewConfigurationType t) {
  if (t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_SUCCESS;
  // PRIMARY_MONO is the core API's other one; the rest belong to extensions the runtime does not offer.
  return t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO ? XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED
                                                      : XR_ERROR_VALIDATION_FAILURE;
}

XrResult xrGetSystem(XrInstance instance, const XrSystemGetInfo* getInfo, XrSystemId* systemId) {
  return guarded("xrGetSystem", [&]() -> XrResult {
    const Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(getInfo, XR_TYPE_SYSTEM_GET_INFO) || systemId == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (getInfo->formFactor == XR_FORM_FACTOR_HANDHELD_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
    if (getInfo->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_VALIDATION_FAILURE;
    if (in->config.refuse_system) {
      report("WEDGE_XR_REFUSE=system: xrGetSystem answers XR_ERROR_FORM_FACTOR_UNAVAILABLE (as if no headset were connected)");
      return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
    }
    *systemId = kSystemId;
    return XR_SUCCESS;
  });
}

XrResult xrGetSystemProperties(XrInstance instance, XrSystemId systemId, XrSystemProperties* properties) {
  return guarded("xrGetSystemProperties", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    if (!has_type(properties, XR_TYPE_SYSTEM_PROPERTIES)) return XR_ERROR_VALIDATION_FAILURE;
    properties->systemId = kSystemId;
    properties->vendorId = 0;
    copy_string(properties->systemName, "Wedge replay: recorded Oculus Touch pair");
    properties->graphicsProperties.maxSwapchainImageWidth = kMaxImageSize;
    properties->graphicsProperties.maxSwapchainImageHeight = kMaxImageSize;
    properties->graphicsProperties.maxLayerCount = kMaxLayers;
    properties->trackingProperties.orientationTracking = XR_TRUE;
    properties->trackingProperties.positionTracking = XR_TRUE;
    return XR_SUCCESS;
  });
}

XrResult xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId systemId, XrViewConfigurationType type,
                                          uint32_t capacity, uint32_t* count, XrEnvironmentBlendMode* modes) {
  return guarded("xrEnumerateEnvironmentBlendModes", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    if (const XrResult r = check_view_configuration(type); r != XR_SUCCESS) return r;
    return two_call(capacity, count, modes, std::vector<XrEnvironmentBlendMode>{XR_ENVIRONMENT_BLEND_MODE_OPAQUE});
  });
}

XrResult xrEnumerateViewConfigurations(XrInstance instance, XrSystemId systemId, uint32_t capacity, uint32_t* count,
                                      XrViewConfigurationType* types) {
  return guarded("xrEnumerateViewConfigurations", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    return two_call(capacity, count, types, std::vector<XrViewConfigurationType>{XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO});
  });
}

XrResult xrGetViewConfigurationProperties(XrInstance instance, XrSystemId systemId, XrViewConfigurationType type,
                                         XrViewConfigurationProperties* properties) {
  return guarded("xrGetViewConfigurationProperties", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    if (!has_type(properties, XR_TYPE_VIEW_CONFIGURATION_PROPERTIES)) return XR_ERROR_VALIDATION_FAILURE;
    if (const XrResult r = check_view_configuration(type); r != XR_SUCCESS) return r;
    properties->viewConfigurationType = type;
    properties->fovMutable = XR_TRUE;
    return XR_SUCCESS;
  });
}

XrResult xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId systemId, XrViewConfigurationType type,
                                          uint32_t capacity, uint32_t* count, XrViewConfigurationView* views) {
  return guarded("xrEnumerateViewConfigurationViews", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    if (const XrResult r = check_view_configuration(type); r != XR_SUCCESS) return r;
    return two_call_structs(capacity, count, views, 2, XR_TYPE_VIEW_CONFIGURATION_VIEW,
                            [&](uint32_t, XrViewConfigurationView& v) {
                              v.recommendedImageRectWidth = in->config.eye_width;
                              v.recommendedImageRectHeight = in->config.eye_height;
                              v.maxImageRectWidth = kMaxImageSize;
                              v.maxImageRectHeight = kMaxImageSize;
                              v.recommendedSwapchainSampleCount = 1;
                              v.maxSwapchainSampleCount = 1;
                            });
  });
}

XrResult xrGetOpenGLGraphicsRequirementsKHR(XrInstance instance, XrSystemId systemId,
                                           XrGraphicsRequirementsOpenGLKHR* graphicsRequirements) {
  return guarded("xrGetOpenGLGraphicsRequirementsKHR", [&]() -> XrResult {
    Instance* in = nullptr;
    if (const XrResult r = check_system(instance, systemId, in); r != XR_SUCCESS) return r;
    if (!has_type(graphicsRequirements, XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR)) return XR_ERROR_VALIDATION_FAILURE;
    graphicsRequirements->minApiVersionSupported = XR_MAKE_VERSION(3, 3, 0);
    graphicsRequirements->maxApiVersionSupported = XR_MAKE_VERSION(4, 6, 0);
    in->gl_requirements_queried = true;
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay
