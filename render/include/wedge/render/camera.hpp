// A camera for the 3D slice space: where it is, what it looks at, and how it projects. Produces the
// view and projection matrices the renderer uploads (column-major, OpenGL clip-space conventions).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

namespace wedge::render {

struct Camera {
  Eigen::Vector3d eye{4.0, 3.0, 6.0};   // m, slice coordinates
  Eigen::Vector3d target{0.0, 0.0, 0.0};
  Eigen::Vector3d up{0.0, 1.0, 0.0};
  double fov_y_degrees = 40.0;          // perspective: vertical field of view
  bool orthographic = false;
  double ortho_height = 4.0;            // m, visible height when orthographic
  double near_plane = 0.05, far_plane = 200.0;  // m
  // A headset eye's asymmetric frustum (OpenXR's XrFovf): the tangents of its angles left, right, down
  // and up of the view axis (left and down negative). When set, they replace fov_y_degrees and the aspect.
  std::optional<std::array<double, 4>> frustum;

  Eigen::Matrix4d view() const;
  Eigen::Matrix4d projection(double aspect) const;  // aspect = width / height
};

}  // namespace wedge::render
