// OpenXR's core and platform headers as the runtime uses them: XR_KHR_opengl_enable with the Xlib binding and
// XR_KHR_convert_timespec_time. The Xlib binding names a few X11/GLX types; they are declared here as opaque
// stand-ins spelled exactly as Xlib and GLX spell them (same ABI: pointers and an unsigned long XID), so no TU of
// the runtime includes the X11 headers, whose macros (Success, None, Bool, Status) collide with Eigen's names.
// The runtime never looks inside them: it only checks that the binding is there.
#pragma once

#include <ctime>  // struct timespec, for XR_USE_TIMESPEC

typedef struct _XDisplay Display;
typedef unsigned long XID;
typedef XID GLXDrawable;
typedef struct __GLXFBConfigRec* GLXFBConfig;
typedef struct __GLXcontextRec* GLXContext;

#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
