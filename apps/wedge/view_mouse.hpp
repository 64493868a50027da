// The viewer's mouse (`wedge view`: platform and mouse, with view_platform.hpp): where each frame's mouse and keys
// come from (GLFW, or a --mouse script for tests and demos), the orbit camera they turn, the mouse as a
// hand of the input layer, and the phone whose tilt the panel, the arrow keys or a script set.
#pragma once

#include <GLFW/glfw3.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli_error.hpp"
#include "wedge/error.hpp"
#include "wedge/render/camera.hpp"
#include "wedge/slicing/pick.hpp"

namespace wedge::cli::viewer {

// The mouse as the viewer sees it in one frame: window pixels, buttons, modifier, wheel. From GLFW, or
// from a --mouse script (JSON Lines {"frame", "x", "y", "left", "right", "shift", "wheel"}, each line
// holding from its frame on; injected events for tests and demos).
struct MouseState {
  double x = 0, y = 0;
  bool left = false, right = false, middle = false, shift = false;
  double wheel = 0;
  std::optional<double> roll, pitch;  // the phone's tilt, degrees (script fields "roll", "pitch", "tilt_w")
  std::optional<bool> tilt_w;
  std::optional<std::vector<double>> w;  // slice offsets, as the sliders set them (script field "w")
  std::optional<std::string> find;       // a body whose centre the slice moves to (script field "find")
  bool fit = false;                      // refit the camera to what the scene does next (script field "fit")
};

// A --mouse script: (frame, the mouse from that frame on), frames increasing.
using MouseScript = std::vector<std::pair<std::int64_t, MouseState>>;

// Reads a --mouse script; throws Failure naming the file and line.
MouseScript read_mouse_script(const std::string& path);

// A script is checked against the scene before any window opens: at most N-3 slice offsets in "w", and
// every "find" naming a bounded body (`body_named(name)`: its id, or nothing).
template <int N, typename BodyNamed>
void check_mouse_script(const MouseScript& script, const std::string& path, const std::string& scene_file,
                        BodyNamed&& body_named) {
  for (const auto& [frame, m] : script) {
    const std::string where = path + ": frame " + std::to_string(frame);
    if (m.w && m.w->size() > std::size_t(std::max(N - 3, 0)))
      throw Failure(where + ": \"w\" has " + std::to_string(m.w->size()) + " offsets; a " + std::to_string(N) +
                    "D scene has " + std::to_string(std::max(N - 3, 0)));
    if (m.find && !body_named(*m.find))
      throw Failure(where + ": \"find\": " + scene_file + " has no bounded body named '" + printable(*m.find) + "'");
  }
}

// An orbiting camera: the fitted camera's target and eye, turned about `up` (yaw) and the screen's right
// axis (pitch), moved across the view (pan) and toward the target (zoom).
struct Orbit {
  render::Camera camera;
  void rotate(double yaw, double pitch);
  void pan(double dx, double dy);
  void zoom(double steps);
  // The mouse on the camera (while no hand holds a body): right drag orbits, middle drag pans, the wheel
  // zooms. dx, dy: the cursor's move since the last frame, px; `height`: the window's, px.
  void follow(const MouseState& mouse, double dx, double dy, int height);
};

// A ray from the camera: origin on the near plane, unit direction.
struct Ray {
  Eigen::Vector3d origin, direction;
};

// The ray through window pixel (x, y) of a view whose left edge is at `left` px, width x height px.
Ray cursor_ray(const render::Camera& camera, double x, double y, int left, int width, int height);

// The mouse as a hand: a left press on a body grabs it at the point under the cursor (picked on the
// slice meshes); dragging moves that point in the plane facing the camera, the wheel moves it in depth;
// a right drag turns the hand (with Shift: in planes with w, the input layer's 4D mode); releasing
// throws. The hand lives in tracking space = slice coordinates (the tracking origin is the slice's).
struct MouseHand {
  bool holding = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // slice coordinates
  double depth = 0.0;                               // m along the camera's forward axis
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
  bool mode4d = false;
  bool ever = false;  // tracked since the first press

  // A left press: grabs the point `hit` picked under the cursor (none: nothing happens) at its depth.
  void press(const std::optional<slicing::Pick>& hit, const render::Camera& camera);
  // A left drag while holding: the point follows `ray` (the cursor's) in the plane facing the camera at
  // the hand's depth, which the wheel scales; with the right button down too, the cursor's move (dx, dy
  // px) turns the hand about the camera's up and right axes.
  void drag(const MouseState& mouse, const Ray& ray, double dx, double dy, const render::Camera& camera);
};

// The phone a viewer user tilts from the panel (or the arrow keys): still, turned by `roll` about its z
// axis (counterclockwise, out of the screen) and `pitch` about its x axis. Once touched it feeds the input
// layer's accelerometer path every step, as a still phone reads: gravity in the device frame.
struct Phone {
  bool active = false;
  float roll = 0.0f, pitch = 0.0f;  // degrees
  bool tilt_w = false;
  Eigen::Vector3d acceleration() const {  // g: Rz(-roll) Rx(-pitch) (0, -1, 0)
    const double r = roll * M_PI / 180.0, p = pitch * M_PI / 180.0;
    return Eigen::AngleAxisd(-r, Eigen::Vector3d::UnitZ()) * (Eigen::AngleAxisd(-p, Eigen::Vector3d::UnitX()) *
                                                             Eigen::Vector3d(0.0, -1.0, 0.0));
  }
  // A script's tilt fields, where it has them (touching the phone); tilting toward w needs a w (`has_w`).
  void take(const MouseState& mouse, bool has_w) {
    if (mouse.roll || mouse.pitch || mouse.tilt_w) active = true;
    if (mouse.roll) roll = float(*mouse.roll);
    if (mouse.pitch) pitch = float(*mouse.pitch);
    if (mouse.tilt_w) tilt_w = *mouse.tilt_w && has_w;
  }
};

// Where each frame's mouse and keys come from: GLFW (the mouse only where the panel does not want it,
// the keys only where it does not type), or the script, which then stands in for both. It keeps the last
// frame's cursor and buttons, for drags and presses.
class MouseInput {
 public:
  explicit MouseInput(MouseScript script) : script_(std::move(script)) {}
  bool scripted() const { return !script_.empty(); }
  // The cursor where the window opened: the first frame's move is measured from it.
  void start(GLFWwindow* window) { glfwGetCursorPos(window, &last_x_, &last_y_); }

  // The mouse of frame `frame` (counted from 1).
  MouseState read(GLFWwindow* window, std::int64_t frame);
  // The C key went down this frame (it toggles the contact marks).
  bool contacts_key(GLFWwindow* window);
  // J went down this frame (it toggles the joint marks).
  bool joints_key(GLFWwindow* window);
  // F went down this frame: refit the camera.
  bool fit_key(GLFWwindow* window);
  // The arrow keys tilt the phone, a degree a frame.
  void tilt_keys(GLFWwindow* window, Phone& phone) const;

  // The cursor's move since the last frame (px), and whether the left button went down in this one.
  double dx(const MouseState& mouse) const { return mouse.x - last_x_; }
  double dy(const MouseState& mouse) const { return mouse.y - last_y_; }
  bool pressed(const MouseState& mouse) const { return mouse.left && !was_left_; }
  // This frame's mouse becomes the last one.
  void end_frame(const MouseState& mouse) {
    was_left_ = mouse.left;
    last_x_ = mouse.x, last_y_ = mouse.y;
  }

 private:
  MouseScript script_;
  std::size_t script_next_ = 0;  // the first script line not yet reached
  MouseState scripted_;          // the mouse as the lines reached so far leave it
  double last_x_ = 0, last_y_ = 0;
  bool was_left_ = false, was_c_ = false, was_f_ = false, was_j_ = false;
  bool key_went_down(GLFWwindow* window, int key, bool& was) const;
};

}  // namespace wedge::cli::viewer
