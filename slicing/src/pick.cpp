// Ray picking against slice meshes (pick.hpp).
#include "wedge/slicing/pick.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace wedge::slicing {

std::optional<Pick> pick(const std::vector<DisplayMesh<3>>& meshes, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& direction, double max_distance) {
  const double length = direction.norm();
  if (!(length > 0.0) || !all_finite(origin) || !all_finite(direction)) return std::nullopt;
  const Eigen::Vector3d d = direction / length;
  std::optional<Pick> best;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const DisplayMesh<3>& mesh = meshes[m];
    for (const auto& cell : mesh.cells) {
      const Eigen::Vector3d &a = mesh.vertices[std::size_t(cell[0])], &b = mesh.vertices[std::size_t(cell[1])],
                            &c = mesh.vertices[std::size_t(cell[2])];
      // Moller-Trumbore: origin + t d = a + u (b - a) + v (c - a), u, v >= 0, u + v <= 1.
      const Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
      const double det = e1.dot(p);
      if (std::abs(det) < 1e-300) continue;  // parallel to the triangle
      const double inv = 1.0 / det;
      const Eigen::Vector3d s = origin - a;
      const double u = s.dot(p) * inv;
      if (u < 0.0 || u > 1.0) continue;
      const Eigen::Vector3d q = s.cross(e1);
      const double v = d.dot(q) * inv;
      if (v < 0.0 || u + v > 1.0) continue;
      const double t = e2.dot(q) * inv;
      if (t < 0.0 || t > max_distance || (best && t >= best->distance)) continue;
      Eigen::Vector3d n = e1.cross(e2).normalized();
      if (n.dot(d) > 0.0) n = -n;
      best = Pick{int(m), t, origin + t * d, n};
    }
  }
  return best;
}

}  // namespace wedge::slicing
