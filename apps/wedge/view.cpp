// wedge view SCENE.json [--w W] [--size WxH] [--subdivisions S] [--play-subdivisions S]
//                        [--replay RECORDING... | --record FILE] [--mouse FILE] [--events FILE] [--contacts]
//                        [--hash] [--frames N --screenshot FILE.png]
//
// The desktop viewer: a window (GLFW, OpenGL 3.3 core) drawing the scene's 3D slice with the same renderer
// as `wedge render`, and a Dear ImGui panel: play, pause, single step, reset, time scale, the slice
// offsets (w in 4D; two or three in 5D and 6D), the bodies and whether the slice meets them (a click
// moves the slice through one), contacts on or off, the phone, the pulse log, and the frame time split
// into physics, slicing and drawing. The camera orbits (right drag), pans (middle drag) and zooms
// (wheel); the 3D view fills the window right of the panel. The mouse is a hand of the input layer
// (grab, drag, turn, throw); --replay drives the scene with recordings instead, as `wedge replay` does.
// Hands, haptic flashes and contact points are drawn over the bodies (view_overlays.hpp). Without a
// display: --frames N draws N frames (each 1/60 s of simulated time while playing) and --screenshot
// writes the last one as PNG, for tests and pictures; with no display at all the viewer exits with code
// 2, naming DISPLAY.
//
// Each frame draws the current state, then advances it, so frame 1 shows step 0: right of the panel, the
// picture `wedge render --steps 0 --size (W-316)xH` draws.
#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <Eigen/Geometry>
#include <chrono>
#include <fstream>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "event_json.hpp"
#include "interrupt.hpp"
#include "replay_input.hpp"
#include "scene_frame.hpp"
#include "scene_slices.hpp"
#include "verbs.hpp"
#include "view_overlays.hpp"
#include "wedge/render/png.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/slicing/pick.hpp"

namespace wedge::cli {

namespace {

constexpr double kFrameTime = 1.0 / 60.0;  // s of simulated time per frame in --frames mode
constexpr float kPanelWidth = 300.0f;      // px: the panel sits at the left edge, this wide
constexpr int kViewLeft = 316;              // px: the 3D view starts right of the panel (and its margins)

std::string g_glfw_error;  // GLFW's last error message (its callback cannot throw)

// GLFW and a window with a current GL 3.3 core context, torn down in order.
class Window {
 public:
  Window(const std::string& scene, int width, int height) {
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
  ~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

// Dear ImGui over the window, torn down in order.
class Gui {
 public:
  explicit Gui(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~Gui() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;
};

// An orbiting camera: the fitted camera's target and eye, turned about `up` (yaw) and the screen's right
// axis (pitch), moved across the view (pan) and toward the target (zoom).
struct Orbit {
  render::Camera camera;
  void rotate(double yaw, double pitch) {
    Eigen::Vector3d offset = camera.eye - camera.target;
    const Eigen::Vector3d right = offset.cross(camera.up).normalized();
    offset = Eigen::AngleAxisd(-yaw, camera.up) * offset;
    const Eigen::Vector3d turned = Eigen::AngleAxisd(pitch, right) * offset;
    if (std::abs(turned.normalized().dot(camera.up)) < 0.98) offset = turned;  // not over the pole
    camera.eye = camera.target + offset;
  }
  void pan(double dx, double dy) {
    const Eigen::Vector3d offset = camera.eye - camera.target;
    const Eigen::Vector3d right = camera.up.cross(offset).normalized(), up = offset.cross(right).normalized();
    const Eigen::Vector3d move = offset.norm() * (-dx * right + dy * up);
    camera.eye += move;
    camera.target += move;
  }
  void zoom(double steps) { camera.eye = camera.target + (camera.eye - camera.target) * std::pow(0.9, steps); }
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
};

std::vector<std::pair<std::int64_t, MouseState>> read_mouse_script(const std::string& path) {
  std::vector<std::pair<std::int64_t, MouseState>> script;
  std::ifstream in(path);
  if (!in) throw Failure(path + ": cannot open the mouse script");
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.empty()) continue;
    try {
      const Json j = Json::parse(text);
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
      const std::int64_t frame = j.at("frame").get<std::int64_t>();
      if (!script.empty() && frame <= script.back().first) throw Failure("frames must increase");
      script.emplace_back(frame, m);
    } catch (const std::exception& e) {
      throw Failure(path + ":" + std::to_string(line) + ": " + e.what());
    }
  }
  return script;
}

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
};

// The ray through window pixel (x, y) of a view whose left edge is at `left` px, width x height px.
std::pair<Eigen::Vector3d, Eigen::Vector3d> cursor_ray(const render::Camera& camera, double x, double y, int left,
                                                       int width, int height) {
  const Eigen::Matrix4d inv = (camera.projection(double(width) / height) * camera.view()).inverse();
  const double nx = 2.0 * (x - left) / width - 1.0, ny = 1.0 - 2.0 * y / height;
  Eigen::Vector4d a = inv * Eigen::Vector4d(nx, ny, -1.0, 1.0), b = inv * Eigen::Vector4d(nx, ny, 1.0, 1.0);
  const Eigen::Vector3d near = a.head<3>() / a[3], far = b.head<3>() / b[3];
  return {near, (far - near).normalized()};
}

template <int N>
int view(const Json& doc, const ViewOptions& o, const std::vector<double>& w0, int width, int height,
         std::int64_t frames, int subdivisions, int play_subdivisions) {
  const std::string& file = o.scene;
  if constexpr (N < 3) {
    (void)doc, (void)w0, (void)width, (void)height, (void)frames, (void)subdivisions, (void)play_subdivisions;
    throw Failure(file + ": a 2D scene has no 3D slice to view (view needs a 3D..6D scene)");
  } else {
    const Scene<N> scene = load_scene<N>(doc, file);
    const double h = scene.timestep;
    World<N> world = scene.make_world(file);
    std::unique_ptr<ReplayInput<N>> replay;  // (not std::optional: GCC 12 warns falsely about its reset)
    if (!o.replay.empty()) replay = std::make_unique<ReplayInput<N>>(scene, world, o.replay, file, h);
    std::vector<double> w = w0;
    w.resize(std::size_t(std::max(N - 3, 0)), 0.0);
    // Round shapes at two levels: `subdivisions` when still, `play_subdivisions` while the scene plays.
    slicing::WorldSlices<N> slices = scene_slices<N>(world, w, subdivisions, file, play_subdivisions);
    std::vector<slicing::DisplayMesh<3>> meshes;
    slices.slice(world, meshes);
    std::vector<Eigen::Vector3d> corners;
    add_box_corners(meshes, corners);
    // The camera is fitted to the view beside the panel, as `wedge render --size (W-316)xH` fits its picture.
    const render::FrameDesc fitted = fitted_frame(scene, world, slices, corners, width - kViewLeft, height);
    // The w sliders' range: every body's hidden coordinates, with room around them.
    double reach = 1.0;
    for (int i = 0; i < world.body_count(); ++i)
      for (int a = 3; a < N; ++a) reach = std::max(reach, std::abs(world.body(BodyId{std::uint32_t(i)}).center[a]) + 1.0);

    // A --mouse script, checked against the scene before any window opens.
    const auto script = o.mouse.empty() ? std::vector<std::pair<std::int64_t, MouseState>>{} : read_mouse_script(o.mouse);
    auto body_named = [&](const std::string& name) -> std::optional<BodyId> {
      for (const auto& e : slices.entries())
        if (world.name(BodyId{std::uint32_t(e.body)}) == name) return BodyId{std::uint32_t(e.body)};
      return std::nullopt;
    };
    for (const auto& [frame, m] : script) {
      const std::string where = o.mouse + ": frame " + std::to_string(frame);
      if (m.w && m.w->size() > std::size_t(std::max(N - 3, 0)))
        throw Failure(where + ": \"w\" has " + std::to_string(m.w->size()) + " offsets; a " + std::to_string(N) +
                      "D scene has " + std::to_string(std::max(N - 3, 0)));
      if (m.find && !body_named(*m.find))
        throw Failure(where + ": \"find\": " + file + " has no bounded body named '" + *m.find + "'");
    }

    Window window(file, width, height);
    render::Renderer renderer;  // needs the window's context
    Gui gui(window.get());
    Orbit orbit{fitted.camera};
    bool playing = true;
    float time_scale = 1.0f;
    double pending = 0.0;  // s of simulated time owed to the clock
    FrameTimes times;
    std::vector<float> wf(w.begin(), w.end());
    auto last = std::chrono::steady_clock::now();
    double last_x = 0, last_y = 0;
    glfwGetCursorPos(window.get(), &last_x, &last_y);
    std::size_t script_next = 0;
    MouseState scripted;
    bool was_left = false, was_c = false;
    MouseHand hand;
    Phone phone;
    // Without recordings the mouse is the right hand of an input layer of its own; tracking space is the
    // slice (origin: the slice's hidden offsets).
    // The scene's tracking space, with its hidden coordinates moved to the viewed slice (unless recording:
    // a recording has no slice offsets, so then the hand stays in the scene's own slice and its samples
    // mean the same to `wedge replay`).
    const bool recording = !o.record.empty();
    recordings::Recording record;  // --record: the mouse hand (and the phone), written on exit
    record.source = "viewer";
    auto mouse_layer = [&] {
      input::SessionSettings<N> settings = session_settings(scene, h);
      if (!recording)
        for (int a = 3; a < N; ++a) settings.interaction.tracking.origin[a] = slices.flat().origin[a];
      auto session = std::make_unique<input::Session<N>>(world, settings);
      session->set_step_function([&file](World<N>& stepped, double step) { checked_step(stepped, step, file); });
      if (recording)  // one sample per step, at its time: replay reads it back exactly
        session->set_observer([&record](const input::InputFrame& f) {
          record.motion.insert(record.motion.end(), f.motion.begin(), f.motion.end());
          if (!f.hands[1].tracked) return;
          recordings::HandSample sample;
          sample.t = f.t;
          sample.hand = recordings::Hand::Right;
          sample.pose.position = f.hands[1].position;
          sample.pose.orientation = f.hands[1].orientation;
          sample.squeeze = f.hands[1].squeeze;
          sample.mode4d = f.hands[1].mode4d;
          record.hands.push_back(sample);
        });
      return session;
    };
    // Slice coordinates of the hand -> tracking coordinates of the scene's interaction.
    auto to_tracking = [&](const Eigen::Vector3d& p) {
      Eigen::Vector3d t = p;
      for (int a = 0; a < std::min(N, 3); ++a)
        t[a] = (slices.flat().origin[a] + p[a] - scene.interaction.origin[a]) / scene.interaction.scale;
      return t;
    };
    std::unique_ptr<input::Session<N>> mouse_in;
    if (!replay) mouse_in = mouse_layer();
    std::vector<std::string> pulse_log;
    std::vector<std::pair<Vec<N>, double>> flashes;  // haptic pulses shown: contact point, until (s)
    std::array<double, input::kHandCount> hand_flash{};  // a hand's marker flashes until this time (s)
    std::vector<slicing::DisplayMesh<3>> markers;
    std::unique_ptr<OutputSink> events;  // --events: grabs, releases, pulses as `wedge replay --events` writes them
    if (!o.events.empty()) events = std::make_unique<OutputSink>(o.events);
    auto log_pulse = [&](const input::HapticPulse<N>& p) {  // the panel's log, flashes at the contact and hand
      char line[160];
      std::snprintf(line, sizeof line, "t %.2f s: %s hand, %s on %s, %.2f", p.t, hand_name(p.hand),
                    world.name(p.held).c_str(), world.name(p.other).c_str(), p.amplitude);
      pulse_log.emplace_back(line);
      flashes.emplace_back(p.point, world.time() + 0.25);
      hand_flash[std::size_t(p.hand)] = world.time() + 0.25;
      if (events) events->write_line(pulse_json(world, p).dump());
    };
    auto log_events = [&](input::Session<N>& session) {
      for (const input::HapticPulse<N>& p : session.pulses()) log_pulse(p);
      if (events)
        for (const input::InteractionEvent<N>& e : session.events()) events->write_line(event_json(world, e).dump());
      session.clear_output();
    };
    // Moves the slice through body `id`'s centre (the panel's list, or a script's "find").
    auto find_body = [&](BodyId id) {  // (and turns the camera to it: the orbit's target moves to its centre)
      for (std::size_t i = 0; i < wf.size(); ++i) wf[i] = float(world.body(id).center[N - 1 - int(i)]);
      const Eigen::Vector3d to = slices.to_slice_point(world.body(id).center) - orbit.camera.target;
      orbit.camera.target += to;
      orbit.camera.eye += to;
    };
    bool show_contacts = o.contacts;
    // Contact marks scale with the bodies: a twentieth of the median bounding radius (5 cm for a unit tesseract).
    const double mark = [&] {
      std::vector<double> r;
      for (const auto& e : slices.entries()) r.push_back(e.radius);
      if (r.empty()) return 0.05;
      std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
      return 0.05 * r[r.size() / 2];
    }();
    std::string hovered;  // the name of the body under the cursor

    for (std::int64_t frame = 1; !glfwWindowShouldClose(window.get()); ++frame) {
      throw_if_interrupted();
      glfwPollEvents();
      // While playing, round shapes are drawn at the coarse level; paused, and in a screenshot, at the fine one.
      const bool last_frame = frames > 0 && frame == frames;
      const slicing::Detail detail = playing && !last_frame ? slicing::Detail::Coarse : slicing::Detail::Fine;
      // The mouse: GLFW's, or the script's when there is one.
      MouseState mouse;
      const ImGuiIO& io = ImGui::GetIO();
      if (!script.empty()) {
        while (script_next < script.size() && script[script_next].first <= frame) scripted = script[script_next++].second;
        mouse = scripted;
        scripted.wheel = 0;  // (a wheel step, a slider move and a find happen once)
        scripted.w.reset();
        scripted.find.reset();
      } else if (!io.WantCaptureMouse) {
        glfwGetCursorPos(window.get(), &mouse.x, &mouse.y);
        mouse.left = glfwGetMouseButton(window.get(), GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        mouse.right = glfwGetMouseButton(window.get(), GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        mouse.middle = glfwGetMouseButton(window.get(), GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
        mouse.shift = glfwGetKey(window.get(), GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                      glfwGetKey(window.get(), GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        mouse.wheel = io.MouseWheel;
      } else {
        glfwGetCursorPos(window.get(), &mouse.x, &mouse.y);
      }
      bool slice_request = false;  // the script moved a slider or asked for a body
      if (mouse.w) {  // (sizes and names were checked with the script)
        for (std::size_t i = 0; i < wf.size(); ++i) wf[i] = i < mouse.w->size() ? float((*mouse.w)[i]) : 0.0f;
        slice_request = true;
      }
      if (mouse.find) {
        find_body(*body_named(*mouse.find));
        slice_request = true;
      }
      if (mouse.roll || mouse.pitch || mouse.tilt_w) phone.active = true;
      if (mouse.roll) phone.roll = float(*mouse.roll);
      if (mouse.pitch) phone.pitch = float(*mouse.pitch);
      if (mouse.tilt_w) phone.tilt_w = *mouse.tilt_w && N >= 4;
      const bool c_key = script.empty() && !io.WantCaptureKeyboard && glfwGetKey(window.get(), GLFW_KEY_C) == GLFW_PRESS;
      if (c_key && !was_c) show_contacts = !show_contacts;
      was_c = c_key;
      if (script.empty() && !io.WantCaptureKeyboard) {  // arrow keys tilt the phone, a degree a frame
        const auto key = [&](int k) { return glfwGetKey(window.get(), k) == GLFW_PRESS; };
        const float dr = float(key(GLFW_KEY_LEFT)) - float(key(GLFW_KEY_RIGHT)),
                    dp = float(key(GLFW_KEY_UP)) - float(key(GLFW_KEY_DOWN));
        if (dr != 0.0f || dp != 0.0f) {
          phone.active = true;
          phone.roll = std::clamp(phone.roll + dr, -90.0f, 90.0f);
          phone.pitch = std::clamp(phone.pitch + dp, -90.0f, 90.0f);
        }
      }
      const double dx = mouse.x - last_x, dy = mouse.y - last_y;
      const Eigen::Vector3d forward = (orbit.camera.target - orbit.camera.eye).normalized();
      const Eigen::Vector3d cam_right = forward.cross(orbit.camera.up).normalized();
      const Eigen::Vector3d cam_up = cam_right.cross(forward);
      if (mouse_in) {
        const auto ray = cursor_ray(orbit.camera, mouse.x, mouse.y, kViewLeft, width - kViewLeft, height);
        if (mouse.left && !was_left) {  // press: grab what is under the cursor
          slices.slice(world, meshes, detail);
          if (const auto hit = slicing::pick(meshes, ray.first, ray.second)) {
            hand.holding = hand.ever = true;
            hand.point = hit->point;
            hand.depth = (hit->point - orbit.camera.eye).dot(forward);
          }
        } else if (mouse.left && hand.holding) {  // drag in the plane facing the camera; the wheel: depth
          hand.depth *= std::pow(1.1, -mouse.wheel);
          const double along = ray.second.dot(forward);
          if (along > 1e-6) hand.point = ray.first + ray.second * ((hand.depth - (ray.first - orbit.camera.eye).dot(forward)) / along);
          if (mouse.right)  // turn the hand about the camera's axes
            hand.turn = (Eigen::AngleAxisd(dx * 0.01, cam_up) * Eigen::AngleAxisd(dy * 0.01, cam_right) * hand.turn)
                            .normalized();  // (unit to round-off, as a recording reads it back)
        } else if (!mouse.left) {
          hand.holding = false;
        }
        hand.mode4d = mouse.shift;
      }
      was_left = mouse.left;
      if (!hand.holding) {  // the camera: right drag orbits, middle drag pans, the wheel zooms
        if (mouse.right) orbit.rotate(dx * 0.005, dy * 0.005);
        if (mouse.middle) orbit.pan(dx / height, dy / height);
        if (mouse.wheel != 0.0) orbit.zoom(mouse.wheel);
      }
      last_x = mouse.x, last_y = mouse.y;

      // Slice and draw the current state.
      int fb_width = 0, fb_height = 0;
      glfwGetFramebufferSize(window.get(), &fb_width, &fb_height);
      auto t0 = std::chrono::steady_clock::now();
      slices.slice(world, meshes, detail);
      const double slicing_time = seconds_since(t0);
      t0 = std::chrono::steady_clock::now();
      render::FrameDesc desc = fitted;
      desc.camera = orbit.camera;
      int in_slice = 0;
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        const SceneBody<N>& sb = scene.bodies[std::size_t(slices.entries()[k].body)];
        render::Color color = render::palette_color(int(k));
        if (sb.color) color = {float((*sb.color)[0]), float((*sb.color)[1]), float((*sb.color)[2])};
        desc.meshes.push_back({&meshes[k], color});
        in_slice += !meshes[k].empty();
      }
      // Markers: the hands (recorded ones, or the mouse while it holds: left cyan, right magenta) and, for
      // a quarter second after a haptic pulse, yellow at its contact point and on the hand's marker, grown
      // by half: a mouse and a screen cannot feel them. Optionally the contacts: orange points, dark normals.
      markers.clear();
      std::vector<render::Color> marker_colors;
      auto add_marker = [&](slicing::DisplayMesh<3> m, render::Color c) {
        markers.push_back(std::move(m));
        marker_colors.push_back(c);
      };
      const render::Color kFlash{1.0f, 0.85f, 0.0f};
      std::erase_if(flashes, [&](const auto& f) { return f.second <= world.time(); });
      const input::Interaction<N>* layer = replay ? &replay->interaction() : nullptr;
      for (int k = 0; k < input::kHandCount; ++k) {
        std::optional<Eigen::Vector3d> at;
        if (layer && layer->tracked(k)) at = slices.to_slice_point(layer->hand_point(k));
        if (!layer && k == 1 && hand.holding) at = hand.point;
        if (!at) continue;
        const bool flash = hand_flash[std::size_t(k)] > world.time();
        add_marker(marker_cube(*at, flash ? 0.06 : 0.04),
                   flash ? kFlash : (k == 0 ? render::Color{0.0f, 0.9f, 0.9f} : render::Color{1.0f, 0.1f, 0.8f}));
      }
      for (const auto& f : flashes) add_marker(marker_cube(slices.to_slice_point(f.first), 0.05), kFlash);
      if (show_contacts) {
        std::vector<bool> in(meshes.size());
        for (std::size_t k = 0; k < meshes.size(); ++k) in[k] = !meshes[k].empty();
        const ContactMarks contacts = contact_marks(world, slices, in);
        for (const auto& [p, n] : contacts.normals) add_marker(needle(p, n, 8 * mark, 0.3 * mark), {0.1f, 0.1f, 0.3f});
        for (const Eigen::Vector3d& p : contacts.points) add_marker(marker_cube(p, mark), {1.0f, 0.2f, 0.0f});
      }
      for (std::size_t k = 0; k < markers.size(); ++k) desc.meshes.push_back({&markers[k], marker_colors[k], true});
      // The body under the cursor (not while holding one), named beside it and marked in the panel's list.
      hovered.clear();
      if (!hand.holding && !mouse.left && !mouse.right && !mouse.middle && mouse.x >= kViewLeft &&
          (!script.empty() || !io.WantCaptureMouse)) {
        const auto ray = cursor_ray(orbit.camera, mouse.x, mouse.y, kViewLeft, width - kViewLeft, height);
        if (const auto hit = slicing::pick(meshes, ray.first, ray.second))
          hovered = world.name(BodyId{std::uint32_t(slices.entries()[hit->mesh].body)});
      }
      glViewport(0, 0, fb_width, fb_height);
      glClearColor(desc.background[0], desc.background[1], desc.background[2], 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      const int left = std::min(kViewLeft * fb_width / width, fb_width - 1);  // (framebuffer px may differ)
      renderer.draw(desc, fb_width - left, fb_height, left, 0);

      // The panel.
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
      ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(fb_height) - 16), ImGuiCond_Always);
      ImGui::Begin("Wedge", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
      ImGui::TextWrapped("%s (%dD)", file.c_str(), N);
      ImGui::Text("t = %.3f s, step %lld", world.time(), (long long)world.step_count());
      if (ImGui::Button(playing ? "Pause" : "Play")) playing = !playing;
      ImGui::SameLine();
      const bool single = ImGui::Button("Step");
      ImGui::SameLine();
      const bool reset = ImGui::Button("Reset");
      ImGui::SliderFloat("time scale", &time_scale, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
      bool moved = slice_request;
      for (std::size_t i = 0; i < wf.size(); ++i) {  // offsets: x_{n-1} first, then x_{n-2} within it
        const int axis = N - 1 - int(i);
        static const char* const kLabels[] = {"x3", "x4", "x5"};
        moved |= ImGui::SliderFloat(N == 4 ? "w" : kLabels[axis - 3], &wf[i], float(-reach), float(reach), "%.3f m");
      }
      ImGui::Separator();
      ImGui::Checkbox("contacts (C)", &show_contacts);
      ImGui::Text("%d of %d bodies in the slice", in_slice, int(meshes.size()));
      ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      ImGui::TextWrapped("(click a body to move the slice through its centre)");
      ImGui::PopStyleColor();
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        const BodyId id{std::uint32_t(slices.entries()[k].body)};
        std::string label = world.name(id);
        if (meshes[k].empty()) label += "  (out of the slice)";
        label += "##" + std::to_string(k);
        if (ImGui::Selectable(label.c_str(), world.name(id) == hovered) && N > 3) {
          find_body(id);
          moved = true;
        }
      }
      ImGui::Separator();
      ImGui::Text("physics %.2f ms", 1e3 * times.physics);
      ImGui::Text("slicing %.2f ms", 1e3 * times.slicing);
      ImGui::Text("drawing %.2f ms", 1e3 * times.drawing);
      ImGui::Text("round shapes: %d subdivisions%s", detail == slicing::Detail::Coarse ? play_subdivisions : subdivisions,
                  detail == slicing::Detail::Coarse && play_subdivisions != subdivisions ? " (playing)" : "");
      ImGui::TextWrapped("Left drag on a body: grab and move it (wheel: depth; right drag: turn it, with Shift into "
                         "w). Release throws. Right drag: orbit. Middle drag: pan. Wheel: zoom.");
      if (mouse_in) {  // the phone: tilts gravity through the input layer, as an accelerometer would
        ImGui::Separator();
        ImGui::Text("phone (tilts gravity; arrow keys too)");
        phone.active |= ImGui::SliderFloat("roll", &phone.roll, -90.0f, 90.0f, "%.0f deg");
        phone.active |= ImGui::SliderFloat("pitch", &phone.pitch, -90.0f, 90.0f, "%.0f deg");
        if (N >= 4) phone.active |= ImGui::Checkbox("tilt toward w", &phone.tilt_w);
        const Vec<N> g = world.gravity();
        ImGui::Text("gravity |g| %.2f m/s^2, %s", g.norm(), phone.active ? "from the phone" : "the scene's");
      }
      ImGui::Separator();
      ImGui::Text("haptic pulses (a mouse cannot feel them):");
      for (std::size_t i = pulse_log.size() > 8 ? pulse_log.size() - 8 : 0; i < pulse_log.size(); ++i)
        ImGui::TextWrapped("%s", pulse_log[i].c_str());
      ImGui::End();
      if (!hovered.empty()) {  // (drawn at the script's cursor too, so that tests and demos show it)
        const float sx = float(fb_width) / float(width), sy = float(fb_height) / float(height);
        const ImVec2 at(float(mouse.x) * sx + 14.0f, float(mouse.y) * sy + 10.0f);
        const ImVec2 size = ImGui::CalcTextSize(hovered.c_str());
        ImDrawList* dl = ImGui::GetForegroundDrawList();
        dl->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + size.x + 4, at.y + size.y + 2), IM_COL32(20, 20, 30, 220), 3.0f);
        dl->AddText(at, IM_COL32(255, 255, 255, 255), hovered.c_str());
      }
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      const double drawing_time = seconds_since(t0);

      if (last_frame) {
        if (!o.screenshot.empty()) {
          std::vector<std::uint8_t> rgba(std::size_t(fb_width) * std::size_t(fb_height) * 4), flipped(rgba.size());
          glReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
          const std::size_t row = std::size_t(fb_width) * 4;
          for (int r = 0; r < fb_height; ++r)  // GL's rows run bottom up
            std::copy_n(&rgba[std::size_t(fb_height - 1 - r) * row], row, &flipped[std::size_t(r) * row]);
          try {
            render::write_png(o.screenshot, flipped, fb_width, fb_height);
          } catch (const Error& e) {
            throw Failure(e.what());
          }
        }
        break;
      }
      glfwSwapBuffers(window.get());

      // Advance: the clock's time (scaled) while playing, one step on request; input from recordings.
      t0 = std::chrono::steady_clock::now();
      const double elapsed = std::min(seconds_since(last), 0.1);
      last = std::chrono::steady_clock::now();
      if (moved) {
        for (std::size_t i = 0; i < wf.size(); ++i) w[i] = wf[i];
        slices.set_offsets(w);
        if (mouse_in && !hand.holding && !recording) mouse_in = mouse_layer();  // the hand moves with the slice
      }
      if (reset) {
        world = scene.make_world(file);
        replay.reset();
        if (!o.replay.empty()) replay = std::make_unique<ReplayInput<N>>(scene, world, o.replay, file, h);
        mouse_in.reset();
        if (!replay) mouse_in = mouse_layer();
        hand = MouseHand{};
        record.hands.clear();  // a recording starts with the world it replays into
        record.motion.clear();
        pending = 0.0;
      }
      if (playing) pending += (frames > 0 ? kFrameTime : elapsed) * time_scale;
      int steps = single ? 1 : 0;
      for (; pending >= h && steps < 64; pending -= h) ++steps;
      if (steps == 64) pending = 0.0;  // too slow to keep up: drop the debt rather than spiral
      for (int s = 0; s < steps; ++s) {
        if (replay) {
          replay->step();
          log_events(replay->session());
          continue;
        }
        input::InputFrame input_frame;
        input_frame.t = double(world.step_count()) * h;
        input::HandInput& right = input_frame.hands[1];
        right.tracked = hand.ever;
        right.position = to_tracking(hand.point);
        right.orientation = hand.turn;
        right.squeeze = hand.holding ? 1.0 : 0.0;
        right.mode4d = hand.mode4d;
        recordings::MotionSample motion;
        if (phone.active) {
          motion.t = input_frame.t;
          motion.acceleration = phone.acceleration();
          motion.tilt = phone.tilt_w;
          input_frame.motion = std::span<const recordings::MotionSample>(&motion, 1);
        }
        mouse_in->step(input_frame);
        log_events(*mouse_in);
      }
      times.add(seconds_since(t0), slicing_time, drawing_time);
    }
    if (events) events->commit();
    if (recording) {
      try {
        recordings::write_recording(o.record, record);
      } catch (const Error& e) {
        throw Failure(e.what());
      }
    }
    if (o.hash)
      std::printf("%lld steps; state hash %016llx\n", (long long)world.step_count(),
                  (unsigned long long)world.state_hash());
    return kExitOk;
  }
}

}  // namespace

CLI::App* add_view_verb(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "view", "Open a window on the scene's 3D slice: play, pause, step, move the slice along w, orbit the camera.");
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--w", o.w, "Slice offsets: W in 4D, W1,W2 in 5D, three in 6D (default 0)")->type_name("W");
  cmd->add_option("--size", o.size, "Window size in pixels (default 1280x720)")->type_name("WxH");
  cmd->add_option("--subdivisions", o.subdivisions, "Tessellation of round shapes (default by dimension)")
      ->type_name("S");
  cmd->add_option("--play-subdivisions", o.play_subdivisions,
                  "Tessellation of round shapes while the scene plays (default 5/8 of --subdivisions: 5 in 4D); "
                  "paused frames and screenshots use --subdivisions")
      ->type_name("S");
  cmd->add_option("--replay", o.replay, "Recordings that drive the scene through the input layer")
      ->type_name("RECORDING...")
      ->expected(1, -1);
  cmd->add_option("--mouse", o.mouse,
                  "Play mouse events from FILE (JSON Lines {\"frame\", \"x\", \"y\", \"left\", \"right\", \"shift\", "
                  "\"wheel\"}) instead of the real mouse")
      ->type_name("FILE");
  cmd->add_option("--record", o.record,
                  "Record the mouse hand to FILE (docs/recording-format.md) on exit; `wedge replay SCENE FILE` "
                  "gives the same state")
      ->type_name("FILE");
  cmd->add_flag("--contacts", o.contacts, "Show contact points and normals from the start (key C toggles them)");
  cmd->add_option("--events", o.events,
                  "Write grabs, releases and haptic pulses to FILE (JSON Lines, as wedge replay --events) on exit")
      ->type_name("FILE");
  cmd->add_flag("--hash", o.hash, "On exit print the number of steps and the final state hash");
  cmd->add_option("--frames", o.frames, "Draw N frames (1/60 s of simulated time each) and exit")->type_name("N");
  cmd->add_option("--screenshot", o.screenshot, "With --frames: write the last frame to FILE.png")
      ->type_name("FILE.png");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_view(const ViewOptions& o) {
  std::int64_t frames = 0;
  if (!o.frames.empty() && (!parse_int64(o.frames, frames) || frames < 1))
    throw Failure(o.scene + ": --frames must be an integer >= 1 (got '" + o.frames + "')");
  if (!o.record.empty() && !o.replay.empty())
    throw Failure(o.scene + ": --record records the mouse, which --replay replaces: give one of them");
  if (!o.events.empty() && (o.events == o.record || o.events == o.screenshot))
    throw Failure(o.scene + ": --events must name a file of its own");
  if (!o.screenshot.empty() && frames == 0)
    throw Failure(o.scene + ": --screenshot needs --frames N (the screenshot is of frame N)");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  const std::vector<double> w = parse_slice_offsets(o.scene, o.w, n);
  const int subdivisions = parse_subdivisions(o.scene, o.subdivisions, n);
  const int play_subdivisions = o.play_subdivisions.empty()
                                    ? default_play_subdivisions(subdivisions)
                                    : parse_subdivisions(o.scene, o.play_subdivisions, n, "--play-subdivisions");
  const Size size = parse_size(o.scene, o.size, 480, 240);  // (room for the panel)
  const int width = size.width, height = size.height;
  return with_dim(n, [&](auto dim) {
    return view<decltype(dim)::value>(doc, o, w, width, height, frames, subdivisions, play_subdivisions);
  });
}

}  // namespace wedge::cli
