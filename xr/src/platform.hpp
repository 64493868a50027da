// OpenXR's platform header with what it needs before it: timespec (XR_KHR_convert_timespec_time) and the
// Xlib / GLX types of XR_KHR_opengl_enable's binding. Internal to xr/.
#pragma once

#include <time.h>
// clang-format off
#include <X11/Xlib.h>
#include <GL/glx.h>
// clang-format on
#undef None  // (X11's macros collide with ordinary names)
#undef Bool
#undef Status
#undef Success
#undef Always

#define XR_USE_TIMESPEC 1
#define XR_USE_PLATFORM_XLIB 1
#define XR_USE_GRAPHICS_API_OPENGL 1
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
