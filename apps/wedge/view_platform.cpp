// The viewer's window, its Dear ImGui context and its screenshot (view_platform.hpp).
#include "view_platform.hpp"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "cli_error.hpp"
#include "wedge/error.hpp"
#include "wedge/render/png.hpp"

namespace wedge::cli::viewer {

namespace {

std::string g_glfw_error;  // GLFW's last error message (its callback cannot throw)

}  // namespace

Window::Window(const std::string& scene, int width, int height) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland))
    throw Failure(scene + ": cannot open a window: DISPLAY is not set (no display to draw on; headless, run it "
                          "under Xvfb: xvfb-run -a wedge view ...)");
  glfwSetErrorCallback([](int, const char* message) { g_glfw_error = message; });
  const std::string where = std::string("DISPLAY=") + (display ? display : "");
  if (!glfwInit()) throw Failure(scene + ": cannot open a window on " + where + ": " + g_glfw_error);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, ("wedge view " + scene).c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Failure(scene + ": cannot open an OpenGL 3.3 window on " + where + ": " + g_glfw_error);
  }
  glfwMakeContextCurrent(window_);
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

Gui::Gui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

Gui::~Gui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void write_screenshot(const std::string& path, int fb_width, int fb_height) {
  std::vector<std::uint8_t> rgba(std::size_t(fb_width) * std::size_t(fb_height) * 4), flipped(rgba.size());
  glReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  const std::size_t row = std::size_t(fb_width) * 4;
  for (int r = 0; r < fb_height; ++r)  // GL's rows run bottom up
    std::copy_n(&rgba[std::size_t(fb_height - 1 - r) * row], row, &flipped[std::size_t(r) * row]);
  try {
    render::write_png(path, flipped, fb_width, fb_height);
  } catch (const Error& e) {
    throw Failure(e.what());
  }
}

}  // namespace wedge::cli::viewer
