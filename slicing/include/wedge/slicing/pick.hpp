// Picking in the 3D slice: which sliced body a ray from the camera meets first, and where (the viewer's
// mouse: the point under the cursor becomes a hand's point). The ray is tested against every triangle of
// the slice meshes (Moller-Trumbore); the hit maps back into the world through the slice's 3-flat.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "wedge/slicing/display_mesh.hpp"
#include "wedge/slicing/slicer.hpp"

namespace wedge::slicing {

struct Pick {
  int mesh = 0;                                     // index into the meshes
  double distance = 0.0;                            // along the (unit) direction, >= 0
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // in slice coordinates
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(); // the triangle's unit normal, facing the ray
};

// The nearest triangle hit along origin + t direction, t in [0, max_distance]; direction need not be
// unit. Empty meshes are skipped. Ties go to the lower mesh index.
std::optional<Pick> pick(const std::vector<DisplayMesh<3>>& meshes, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& direction, double max_distance = 1e9);

// A point of the slice's 3-flat (slice coordinates) in the world: origin + frame p.
template <int N>
Vec<N> slice_to_world(const Flat3<N>& flat, const Eigen::Vector3d& p) {
  return flat.origin + flat.frame * p;
}

}  // namespace wedge::slicing
