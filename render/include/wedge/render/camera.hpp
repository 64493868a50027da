// A camera for the 3D slice space: where it is, what it looks at, and how it projects. Produces the
// view and projection matrices the renderer uploads (column-major, OpenGL clip-space conventions).
#pragma once

#include <Eigen/Core>

namespace wedge::render {

struct Camera {
  Eigen::Vector3d eye{4.0, 3.0, 6.0};   // m, slice coordinates
  Eigen::Vector3d target{0.0, 0.0, 0.0};
  Eigen::Vector3d up{0.0, 1.0, 0.0};
  double fov_y_degrees = 40.0;          // perspective: vertical field of view
  bool orthographic = false;
  double ortho_height = 4.0;            // m, visible height when orthographic
  double near_plane = 0.05, far_plane = 200.0;  // m

  Eigen::Matrix4d view() const;
  Eigen::Matrix4d projection(double aspect) const;  // aspect = width / height
};

}  // namespace wedge::render
