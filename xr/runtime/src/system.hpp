// The system's constants, shared by the files that check against them.
#pragma once

#include "xr_platform.hpp"

namespace wedge::xr_replay {

inline constexpr XrSystemId kSystemId = 1;
inline constexpr uint32_t kMaxImageSize = 4096;  // swapchain width and height
inline constexpr uint32_t kMaxLayers = 16;       // composition layers per frame (the spec's minimum)
inline constexpr uint32_t kViewCount = 2;        // PRIMARY_STEREO

// XR_SUCCESS for PRIMARY_STEREO; XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED for PRIMARY_MONO (the core
// API's other type); XR_ERROR_VALIDATION_FAILURE for anything else (other types need extensions the runtime
// does not offer, so they are not valid values here).
XrResult check_view_configuration(XrViewConfigurationType t);

}  // namespace wedge::xr_replay
