// xrGetInstanceProcAddr: every core OpenXR 1.0 function by name, plus the functions of the extensions the
// instance enabled. The loader asks for all of them right after xrCreateInstance and calls through what it
// gets; a name not in the table is XR_ERROR_FUNCTION_UNSUPPORTED.
#include <cstring>
#include <string_view>

#include "api.hpp"
#include "registry.hpp"

namespace wedge::xr_replay {

namespace {

enum class Needs : uint8_t { Core, OpenGL, Timespec };

struct Entry {
  std::string_view name;
  PFN_xrVoidFunction function;
  Needs needs;
};

// The static_cast checks each function against its PFN_ type from openxr.h.
#define WEDGE_XR_ENTRY(fn, needs) \
  Entry { #fn, reinterpret_cast<PFN_xrVoidFunction>(static_cast<PFN_##fn>(&fn)), needs }
#define CORE(fn) WEDGE_XR_ENTRY(fn, Needs::Core)

// The 55 commands of OpenXR 1.0 (the spec's command list, in its order), then the extensions'.
const Entry kTable[] = {
    CORE(xrGetInstanceProcAddr),
    CORE(xrEnumerateApiLayerProperties),
    CORE(xrEnumerateInstanceExtensionProperties),
    CORE(xrCreateInstance),
    CORE(xrDestroyInstance),
    CORE(xrGetInstanceProperties),
    CORE(xrPollEvent),
    CORE(xrResultToString),
    CORE(xrStructureTypeToString),
    CORE(xrGetSystem),
    CORE(xrGetSystemProperties),
    CORE(xrEnumerateEnvironmentBlendModes),
    CORE(xrCreateSession),
    CORE(xrDestroySession),
    CORE(xrEnumerateReferenceSpaces),
    CORE(xrCreateReferenceSpace),
    CORE(xrGetReferenceSpaceBoundsRect),
    CORE(xrCreateActionSpace),
    CORE(xrLocateSpace),
    CORE(xrDestroySpace),
    CORE(xrEnumerateViewConfigurations),
    CORE(xrGetViewConfigurationProperties),
    CORE(xrEnumerateViewConfigurationViews),
    CORE(xrEnumerateSwapchainFormats),
    CORE(xrCreateSwapchain),
    CORE(xrDestroySwapchain),
    CORE(xrEnumerateSwapchainImages),
    CORE(xrAcquireSwapchainImage),
    CORE(xrWaitSwapchainImage),
    CORE(xrReleaseSwapchainImage),
    CORE(xrBeginSession),
    CORE(xrEndSession),
    CORE(xrRequestExitSession),
    CORE(xrWaitFrame),
    CORE(xrBeginFrame),
    CORE(xrEndFrame),
    CORE(xrLocateViews),
    CORE(xrStringToPath),
    CORE(xrPathToString),
    CORE(xrCreateActionSet),
    CORE(xrDestroyActionSet),
    CORE(xrCreateAction),
    CORE(xrDestroyAction),
    CORE(xrSuggestInteractionProfileBindings),
    CORE(xrAttachSessionActionSets),
    CORE(xrGetCurrentInteractionProfile),
    CORE(xrGetActionStateBoolean),
    CORE(xrGetActionStateFloat),
    CORE(xrGetActionStateVector2f),
    CORE(xrGetActionStatePose),
    CORE(xrSyncActions),
    CORE(xrEnumerateBoundSourcesForAction),
    CORE(xrGetInputSourceLocalizedName),
    CORE(xrApplyHapticFeedback),
    CORE(xrStopHapticFeedback),
    WEDGE_XR_ENTRY(xrGetOpenGLGraphicsRequirementsKHR, Needs::OpenGL),
    WEDGE_XR_ENTRY(xrConvertTimespecTimeToTimeKHR, Needs::Timespec),
    WEDGE_XR_ENTRY(xrConvertTimeToTimespecTimeKHR, Needs::Timespec),
};
static_assert(sizeof(kTable) / sizeof(kTable[0]) == 55 + 3);

#undef CORE
#undef WEDGE_XR_ENTRY

const Entry* lookup(std::string_view name) {
  for (const Entry& e : kTable)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace

XrResult xrGetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  return guarded("xrGetInstanceProcAddr", [&]() -> XrResult {
    if (function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    *function = nullptr;
    if (name == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const Entry* e = lookup(name);
    if (instance == XR_NULL_HANDLE) {
      // Without an instance only what creates one may be asked for (and this function itself).
      const std::string_view n(name);
      if (n != "xrEnumerateInstanceExtensionProperties" && n != "xrEnumerateApiLayerProperties" &&
          n != "xrCreateInstance" && n != "xrGetInstanceProcAddr")
        return XR_ERROR_HANDLE_INVALID;
      *function = e->function;
      return XR_SUCCESS;
    }
    const Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (e == nullptr) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if ((e->needs == Needs::OpenGL && !in->opengl_enabled) || (e->needs == Needs::Timespec && !in->timespec_enabled))
      return XR_ERROR_FUNCTION_UNSUPPORTED;  // an extension's functions exist only where it is enabled
    *function = e->function;
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay
