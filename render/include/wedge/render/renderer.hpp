// The slice renderer: draws 3D slice meshes (wedge::slicing::DisplayMesh<3>) with a colour per body,
// diffuse + specular lighting, a ground grid and the bodies' shadows on it into whatever framebuffer is
// bound, with OpenGL 3.3 core shaders. It knows nothing about where its pixels go: the offscreen OSMesa context
// (offscreen_context.hpp) today, a window or an OpenXR swapchain image later. A current OpenGL 3.3
// core context is required for the Renderer's whole life.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "wedge/render/camera.hpp"
#include "wedge/slicing/display_mesh.hpp"

namespace wedge::render {

using Color = std::array<float, 3>;  // linear RGB in [0, 1]

struct MeshDraw {
  const slicing::DisplayMesh<3>* mesh = nullptr;
  Color color{0.8f, 0.8f, 0.8f};
  // Drawn after everything else and over it (depth-tested only among overlays), with no shadow: markers
  // that must stay visible inside or behind bodies (a viewer's hands, contact points).
  bool overlay = false;
};

// The ground: an infinite grid on the plane {y : normal . y = offset}, drawn out to `extent` metres
// around the camera target's foot point. Each mesh casts a shadow on it straight down (along -normal),
// so the gap between a body and its shadow shows its height: the ground there takes `shadow_strength`
// of its light away for a body touching it, half that at `shadow_fade` metres up (the body's lowest
// point). Overlapping shadows darken once, to the darkest of them.
struct Ground {
  bool enabled = false;
  Eigen::Vector3d normal{0.0, 1.0, 0.0};
  double offset = 0.0;     // m
  double spacing = 0.5;    // m between grid lines
  double extent = 40.0;    // m
  Color color{0.55f, 0.57f, 0.6f};
  Color line_color{0.3f, 0.32f, 0.36f};
  bool shadows = true;
  double shadow_strength = 0.55;  // in [0, 1]
  double shadow_fade = 4.0;       // m
};

struct FrameDesc {
  Camera camera;
  std::vector<MeshDraw> meshes;
  Ground ground;
  Color background{0.93f, 0.94f, 0.96f};
  Eigen::Vector3d light_direction{-0.4, -1.0, -0.3};  // direction the light travels
};

class Renderer {
 public:
  Renderer();  // compiles the shaders; throws wedge::Error if there is no usable GL 3.3 context
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Clears the bound framebuffer's viewport (x, y, width, height), pixels from the lower left, and draws the
  // frame into it.
  void draw(const FrameDesc& frame, int width, int height, int x = 0, int y = 0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A distinct colour for body i (a fixed palette, repeated).
Color palette_color(int i);

}  // namespace wedge::render
