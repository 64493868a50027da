// A stand-in for XF86VidModeGetAllModeLines, preloaded (LD_PRELOAD) into hello_xr when it runs under Xvfb.
// Xvfb has no XFree86-VidModeExtension, and hello_xr's window code (ksGpuWindow_Create, OpenXR SDK 1.0.20)
// reads the first mode line to learn the desktop's refresh rate without checking that the call succeeded,
// so it crashes before it ever reaches OpenXR. When the real call fails, this answers with one 60 Hz
// 1280x1024 mode line instead. It changes nothing that the runtime sees.
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>

extern "C" {

typedef struct _XDisplay Display;

// XF86VidModeModeInfo, laid out as libXxf86vm's <X11/extensions/xf86vmode.h> declares it.
struct ModeInfo {
  unsigned int dotclock;  // kHz
  unsigned short hdisplay, hsyncstart, hsyncend, htotal, hskew;
  unsigned short vdisplay, vsyncstart, vsyncend, vtotal;
  unsigned int flags;
  int privsize;
  int* c_private;
};

__attribute__((visibility("default"))) int XF86VidModeGetAllModeLines(Display* display, int screen, int* count,
                                                                       ModeInfo*** modes) {
  using Real = int (*)(Display*, int, int*, ModeInfo***);
  static const Real real = reinterpret_cast<Real>(dlsym(RTLD_NEXT, "XF86VidModeGetAllModeLines"));
  if (real != nullptr && real(display, screen, count, modes) && *count > 0) return 1;
  // One block holding the pointer array and the mode, as libXxf86vm allocates it (the caller XFree()s it).
  void* block = std::calloc(1, sizeof(ModeInfo*) + sizeof(ModeInfo));
  if (block == nullptr) return 0;
  auto** list = static_cast<ModeInfo**>(block);
  auto* mode = reinterpret_cast<ModeInfo*>(list + 1);
  // 1280x1024 at 60 Hz: dotclock = htotal * vtotal * 60 / 1000 kHz.
  mode->hdisplay = 1280;
  mode->vdisplay = 1024;
  mode->htotal = 1688;
  mode->vtotal = 1066;
  mode->dotclock = 1688u * 1066u * 60u / 1000u;
  list[0] = mode;
  *modes = list;
  *count = 1;
  return 1;
}

}  // extern "C"
