// The viewer's mouse: the --mouse script, the orbit camera, the mouse hand and GLFW's mouse and keys
// (view_mouse.hpp).
#include "view_mouse.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <fstream>
#include <limits>

#include "scenes.hpp"
#include "wedge/fp_env.hpp"

namespace wedge::cli::viewer {

MouseScript read_mouse_script(const std::string& path) {
  MouseScript script;
  std::ifstream in(path);
  if (!in) throw Failure(path + ": cannot open the mouse script");
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.empty()) continue;
    try {
      const Json j = [&] {
        const ExpectedFpExceptions quiet;  // 1e999 overflows while parsed: reported as bad JSON
        return Json::parse(text);
      }();
      MouseState m;
      m.x = j.at("x").get<double>();
      m.y = j.at("y").get<double>();
      m.left = j.value("left", false);
      m.right = j.value("right", false);
      m.shift = j.value("shift", false);
      m.wheel = j.value("wheel", 0.0);
      if (j.contains("roll")) m.roll = j.at("roll").get<double>();
      if (j.contains("pitch")) m.pitch = j.at("pitch").get<double>();
      if (j.contains("tilt_w")) m.tilt_w = j.at("tilt_w").get<bool>();
      if (j.contains("w"))
        m.w = j.at("w").is_array() ? j.at("w").get<std::vector<double>>() : std::vector<double>{j.at("w").get<double>()};
      if (j.contains("find")) m.find = j.at("find").get<std::string>();
      m.fit = j.value("fit", false);
      // (a whole number: JSON's 5.5e68 or 1.5 is not a frame, and converting it would be undefined)
      const Json& f = j.at("frame");
      if (!f.is_number_integer() ||
          (f.is_number_unsigned() && f.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max())))
        throw Failure("\"frame\" must be a whole number of frames, got " + f.dump());
      const std::int64_t frame = f.get<std::int64_t>();
      if (!script.empty() && frame <= script.back().first) throw Failure("frames must increase");
      script.emplace_back(frame, m);
    } catch (const std::exception& e) {
      throw Failure(path + ":" + std::to_string(line) + ": " + e.what());
    }
  }
  return script;
}

// ---- The orbit camera -------------------------------------------------------------------------------

void Orbit::rotate(double yaw, double pitch) {
  Eigen::Vector3d offset = camera.eye - camera.target;
  const Eigen::Vector3d right = offset.cross(camera.up).normalized();
  offset = Eigen::AngleAxisd(-yaw, camera.up) * offset;
  const Eigen::Vector3d turned = Eigen::AngleAxisd(pitch, right) * offset;
  if (std::abs(turned.normalized().dot(camera.up)) < 0.98) offset = turned;  // not over the pole
  camera.eye = camera.target + offset;
}

void Orbit::pan(double dx, double dy) {
  const Eigen::Vector3d offset = camera.eye - camera.target;
  const Eigen::Vector3d right = camera.up.cross(offset).normalized(), up = offset.cross(right).normalized();
  const Eigen::Vector3d move = offset.norm() * (-dx * right + dy * up);
  camera.eye += move;
  camera.target += move;
}

void Orbit::zoom(double steps) { camera.eye = camera.target + (camera.eye - camera.target) * std::pow(0.9, steps); }

void Orbit::follow(const MouseState& mouse, double dx, double dy, int height) {
  if (mouse.right) rotate(dx * 0.005, dy * 0.005);
  if (mouse.middle) pan(dx / height, dy / height);
  if (mouse.wheel != 0.0) zoom(mouse.wheel);
}

Ray cursor_ray(const render::Camera& camera, double x, double y, int left, int width, int height) {
  const Eigen::Matrix4d inv = (camera.projection(double(width) / height) * camera.view()).inverse();
  const double nx = 2.0 * (x - left) / width - 1.0, ny = 1.0 - 2.0 * y / height;
  Eigen::Vector4d a = inv * Eigen::Vector4d(nx, ny, -1.0, 1.0), b = inv * Eigen::Vector4d(nx, ny, 1.0, 1.0);
  const Eigen::Vector3d near = a.head<3>() / a[3], far = b.head<3>() / b[3];
  return {near, (far - near).normalized()};
}

// ---- The mouse hand ---------------------------------------------------------------------------------

namespace {

// The camera's forward (toward the target), right and up axes, orthonormal.
struct CameraAxes {
  Eigen::Vector3d forward, right, up;
  explicit CameraAxes(const render::Camera& camera)
      : forward((camera.target - camera.eye).normalized()),
        right(forward.cross(camera.up).normalized()),
        up(right.cross(forward)) {}
};

}  // namespace

void MouseHand::press(const std::optional<slicing::Pick>& hit, const render::Camera& camera) {
  if (!hit) return;
  holding = ever = true;
  point = hit->point;
  depth = (hit->point - camera.eye).dot(CameraAxes(camera).forward);
}

void MouseHand::drag(const MouseState& mouse, const Ray& ray, double dx, double dy, const render::Camera& camera) {
  const CameraAxes axes(camera);
  depth *= std::pow(1.1, -mouse.wheel);
  const double along = ray.direction.dot(axes.forward);
  if (along > 1e-6)
    point = ray.origin + ray.direction * ((depth - (ray.origin - camera.eye).dot(axes.forward)) / along);
  if (mouse.right)  // turn the hand about the camera's axes
    turn = (Eigen::AngleAxisd(dx * 0.01, axes.up) * Eigen::AngleAxisd(dy * 0.01, axes.right) * turn)
               .normalized();  // (unit to round-off, as a recording reads it back)
}

// ---- GLFW's mouse and keys, or the script -----------------------------------------------------------

MouseState MouseInput::read(GLFWwindow* window, std::int64_t frame) {
  MouseState mouse;
  const ImGuiIO& io = ImGui::GetIO();
  if (scripted()) {
    while (script_next_ < script_.size() && script_[script_next_].first <= frame)
      scripted_ = script_[script_next_++].second;
    mouse = scripted_;
    scripted_.wheel = 0;  // (a wheel step, a slider move and a find happen once)
    scripted_.w.reset();
    scripted_.find.reset();
    scripted_.fit = false;
  } else if (!io.WantCaptureMouse) {
    glfwGetCursorPos(window, &mouse.x, &mouse.y);
    mouse.left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    mouse.right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    mouse.middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    mouse.shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                  glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    mouse.wheel = io.MouseWheel;
  } else {  // (over the panel: the cursor only, for the hover label)
    glfwGetCursorPos(window, &mouse.x, &mouse.y);
  }
  return mouse;
}

bool MouseInput::key_went_down(GLFWwindow* window, int key, bool& was) const {
  const bool down = !scripted() && !ImGui::GetIO().WantCaptureKeyboard && glfwGetKey(window, key) == GLFW_PRESS;
  const bool went_down = down && !was;
  was = down;
  return went_down;
}

bool MouseInput::contacts_key(GLFWwindow* window) { return key_went_down(window, GLFW_KEY_C, was_c_); }
bool MouseInput::joints_key(GLFWwindow* window) { return key_went_down(window, GLFW_KEY_J, was_j_); }
bool MouseInput::fit_key(GLFWwindow* window) { return key_went_down(window, GLFW_KEY_F, was_f_); }

void MouseInput::tilt_keys(GLFWwindow* window, Phone& phone) const {
  if (scripted() || ImGui::GetIO().WantCaptureKeyboard) return;
  const auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS; };
  const float dr = float(key(GLFW_KEY_LEFT)) - float(key(GLFW_KEY_RIGHT)),
              dp = float(key(GLFW_KEY_UP)) - float(key(GLFW_KEY_DOWN));
  if (dr != 0.0f || dp != 0.0f) {
    phone.active = true;
    phone.roll = std::clamp(phone.roll + dr, -90.0f, 90.0f);
    phone.pitch = std::clamp(phone.pitch + dp, -90.0f, 90.0f);
  }
}

}  // namespace wedge::cli::viewer
