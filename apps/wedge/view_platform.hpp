// The viewer's platform (`wedge view`: platform and mouse, with view_mouse.hpp): GLFW with one OpenGL 3.3 core
// window, Dear ImGui over it, the screen layout the panel and the 3D view share, the frame clock, and
// the framebuffer written as PNG (--screenshot).
#pragma once

#include <GLFW/glfw3.h>

#include <chrono>
#include <string>

namespace wedge::cli::viewer {

constexpr double kFrameTime = 1.0 / 60.0;  // s of simulated time per frame in --frames mode
constexpr float kPanelWidth = 300.0f;      // px: the panel sits at the left edge, this wide
constexpr int kViewLeft = 316;              // px: the 3D view starts right of the panel (and its margins)
constexpr double kFitSeconds = 3.0;         // s: the camera frames what the scene does over this much time ahead

// GLFW and a window with a current GL 3.3 core context, torn down in order. Without a display (neither
// DISPLAY nor WAYLAND_DISPLAY set) it throws a Failure naming DISPLAY before GLFW is touched.
class Window {
 public:
  Window(const std::string& scene, int width, int height);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

// Dear ImGui over the window, torn down in order.
class Gui {
 public:
  explicit Gui(GLFWwindow* window);
  ~Gui();
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;
};

// Seconds per part of a frame, smoothed for display.
struct FrameTimes {
  double physics = 0, slicing = 0, drawing = 0;
  void add(double p, double s, double d) {
    const double a = 0.1;
    physics += a * (p - physics);
    slicing += a * (s - slicing);
    drawing += a * (d - drawing);
  }
};

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The framebuffer (fb_width x fb_height px) as a PNG at `path`, rows top down. Throws Failure.
void write_screenshot(const std::string& path, int fb_width, int fb_height);

}  // namespace wedge::cli::viewer
