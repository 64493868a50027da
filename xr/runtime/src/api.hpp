// Every OpenXR entry point the runtime implements, by the file that implements it. They are reached only
// through xrGetInstanceProcAddr (dispatch.cpp), never exported.
#pragma once

#include "xr_platform.hpp"

namespace wedge::xr_replay {

#define WEDGE_XR_API XRAPI_ATTR XrResult XRAPI_CALL

// dispatch.cpp
WEDGE_XR_API xrGetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function);

// instance.cpp: instances, extensions, XR_KHR_convert_timespec_time
WEDGE_XR_API xrEnumerateApiLayerProperties(uint32_t capacity, uint32_t* count, XrApiLayerProperties* properties);
WEDGE_XR_API xrEnumerateInstanceExtensionProperties(const char* layerName, uint32_t capacity, uint32_t* count,
                                                     XrExtensionProperties* properties);
WEDGE_XR_API xrCreateInstance(const XrInstanceCreateInfo* createInfo, XrInstance* instance);
WEDGE_XR_API xrDestroyInstance(XrInstance instance);
WEDGE_XR_API xrGetInstanceProperties(XrInstance instance, XrInstanceProperties* properties);
WEDGE_XR_API xrConvertTimespecTimeToTimeKHR(XrInstance instance, const struct timespec* timespecTime, XrTime* time);
WEDGE_XR_API xrConvertTimeToTimespecTimeKHR(XrInstance instance, XrTime time, struct timespec* timespecTime);

// strings.cpp
WEDGE_XR_API xrResultToString(XrInstance instance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]);
WEDGE_XR_API xrStructureTypeToString(XrInstance instance, XrStructureType value,
                                     char buffer[XR_MAX_STRUCTURE_NAME_SIZE]);

// system.cpp: the one HMD system, its views, blend mode and OpenGL requirements
WEDGE_XR_API xrGetSystem(XrInstance instance, const XrSystemGetInfo* getInfo, XrSystemId* systemId);
WEDGE_XR_API xrGetSystemProperties(XrInstance instance, XrSystemId systemId, XrSystemProperties* properties);
WEDGE_XR_API xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId systemId,
                                              XrViewConfigurationType viewConfigurationType, uint32_t capacity,
                                              uint32_t* count, XrEnvironmentBlendMode* modes);
WEDGE_XR_API xrEnumerateViewConfigurations(XrInstance instance, XrSystemId systemId, uint32_t capacity,
                                           uint32_t* count, XrViewConfigurationType* types);
WEDGE_XR_API xrGetViewConfigurationProperties(XrInstance instance, XrSystemId systemId,
                                              XrViewConfigurationType viewConfigurationType,
                                              XrViewConfigurationProperties* properties);
WEDGE_XR_API xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId systemId,
                                               XrViewConfigurationType viewConfigurationType, uint32_t capacity,
                                               uint32_t* count, XrViewConfigurationView* views);
WEDGE_XR_API xrGetOpenGLGraphicsRequirementsKHR(XrInstance instance, XrSystemId systemId,
                                                XrGraphicsRequirementsOpenGLKHR* graphicsRequirements);

// events.cpp
WEDGE_XR_API xrPollEvent(XrInstance instance, XrEventDataBuffer* eventData);

// session.cpp: the session and its state machine
WEDGE_XR_API xrCreateSession(XrInstance instance, const XrSessionCreateInfo* createInfo, XrSession* session);
WEDGE_XR_API xrDestroySession(XrSession session);
WEDGE_XR_API xrBeginSession(XrSession session, const XrSessionBeginInfo* beginInfo);
WEDGE_XR_API xrEndSession(XrSession session);
WEDGE_XR_API xrRequestExitSession(XrSession session);

// frames.cpp: the frame loop on the deterministic clock, layer checks, frame capture
WEDGE_XR_API xrWaitFrame(XrSession session, const XrFrameWaitInfo* frameWaitInfo, XrFrameState* frameState);
WEDGE_XR_API xrBeginFrame(XrSession session, const XrFrameBeginInfo* frameBeginInfo);
WEDGE_XR_API xrEndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo);

// spaces.cpp: reference and action spaces, views
WEDGE_XR_API xrEnumerateReferenceSpaces(XrSession session, uint32_t capacity, uint32_t* count,
                                        XrReferenceSpaceType* spaces);
WEDGE_XR_API xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* createInfo, XrSpace* space);
WEDGE_XR_API xrGetReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType referenceSpaceType,
                                           XrExtent2Df* bounds);
WEDGE_XR_API xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* createInfo, XrSpace* space);
WEDGE_XR_API xrLocateSpace(XrSpace space, XrSpace baseSpace, XrTime time, XrSpaceLocation* location);
WEDGE_XR_API xrDestroySpace(XrSpace space);
WEDGE_XR_API xrLocateViews(XrSession session, const XrViewLocateInfo* viewLocateInfo, XrViewState* viewState,
                           uint32_t capacity, uint32_t* count, XrView* views);

// swapchain.cpp: OpenGL swapchains
WEDGE_XR_API xrEnumerateSwapchainFormats(XrSession session, uint32_t capacity, uint32_t* count, int64_t* formats);
WEDGE_XR_API xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* createInfo, XrSwapchain* swapchain);
WEDGE_XR_API xrDestroySwapchain(XrSwapchain swapchain);
WEDGE_XR_API xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t capacity, uint32_t* count,
                                        XrSwapchainImageBaseHeader* images);
WEDGE_XR_API xrAcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo* acquireInfo,
                                     uint32_t* index);
WEDGE_XR_API xrWaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo* waitInfo);
WEDGE_XR_API xrReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo* releaseInfo);

// actions.cpp: paths, action sets and actions
WEDGE_XR_API xrStringToPath(XrInstance instance, const char* pathString, XrPath* path);
WEDGE_XR_API xrPathToString(XrInstance instance, XrPath path, uint32_t capacity, uint32_t* count, char* buffer);
WEDGE_XR_API xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* createInfo, XrActionSet* actionSet);
WEDGE_XR_API xrDestroyActionSet(XrActionSet actionSet);
WEDGE_XR_API xrCreateAction(XrActionSet actionSet, const XrActionCreateInfo* createInfo, XrAction* action);
WEDGE_XR_API xrDestroyAction(XrAction action);

// bindings.cpp: suggested bindings, attaching, the current profile, bound sources
WEDGE_XR_API xrSuggestInteractionProfileBindings(XrInstance instance,
                                                 const XrInteractionProfileSuggestedBinding* suggestedBindings);
WEDGE_XR_API xrAttachSessionActionSets(XrSession session, const XrSessionActionSetsAttachInfo* attachInfo);
WEDGE_XR_API xrGetCurrentInteractionProfile(XrSession session, XrPath topLevelUserPath,
                                            XrInteractionProfileState* interactionProfile);
WEDGE_XR_API xrEnumerateBoundSourcesForAction(XrSession session, const XrBoundSourcesForActionEnumerateInfo* enumerateInfo,
                                              uint32_t capacity, uint32_t* count, XrPath* sources);
WEDGE_XR_API xrGetInputSourceLocalizedName(XrSession session, const XrInputSourceLocalizedNameGetInfo* getInfo,
                                           uint32_t capacity, uint32_t* count, char* buffer);

// action_state.cpp: xrSyncActions and the action states
WEDGE_XR_API xrSyncActions(XrSession session, const XrActionsSyncInfo* syncInfo);
WEDGE_XR_API xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStateBoolean* state);
WEDGE_XR_API xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStateFloat* state);
WEDGE_XR_API xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* getInfo,
                                      XrActionStateVector2f* state);
WEDGE_XR_API xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* getInfo, XrActionStatePose* state);

// haptics.cpp
WEDGE_XR_API xrApplyHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo,
                                   const XrHapticBaseHeader* hapticFeedback);
WEDGE_XR_API xrStopHapticFeedback(XrSession session, const XrHapticActionInfo* hapticActionInfo);

}  // namespace wedge::xr_replay
