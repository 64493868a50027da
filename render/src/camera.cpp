#include "wedge/render/camera.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace wedge::render {

Eigen::Matrix4d Camera::view() const {
  const Eigen::Vector3d f = (target - eye).normalized();
  Eigen::Vector3d s = f.cross(up);
  if (s.squaredNorm() < 1e-20) s = f.cross(Eigen::Vector3d::UnitX()).squaredNorm() > 1e-20 ? f.cross(Eigen::Vector3d::UnitX())
                                                                                             : f.cross(Eigen::Vector3d::UnitZ());
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d Camera::projection(double aspect) const {
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  const double n = near_plane, f = far_plane;
  if (orthographic) {
    const double t = ortho_height / 2, r = t * aspect;
    p(0, 0) = 1 / r;
    p(1, 1) = 1 / t;
    p(2, 2) = -2 / (f - n);
    p(2, 3) = -(f + n) / (f - n);
    p(3, 3) = 1;
  } else if (frustum) {  // glFrustum with l, r, b, t = n times the tangents
    const auto [l, r, b, t] = *frustum;
    p(0, 0) = 2 / (r - l);
    p(0, 2) = (r + l) / (r - l);
    p(1, 1) = 2 / (t - b);
    p(1, 2) = (t + b) / (t - b);
    p(2, 2) = -(f + n) / (f - n);
    p(2, 3) = -2 * f * n / (f - n);
    p(3, 2) = -1;
  } else {
    const double t = 1.0 / std::tan(fov_y_degrees * M_PI / 360.0);
    p(0, 0) = t / aspect;
    p(1, 1) = t;
    p(2, 2) = -(f + n) / (f - n);
    p(2, 3) = -2 * f * n / (f - n);
    p(3, 2) = -1;
  }
  return p;
}

}  // namespace wedge::render
