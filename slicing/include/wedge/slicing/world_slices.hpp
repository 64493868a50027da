// The 3D view of a World, shared by `wedge render`, `wedge slice`, the desktop viewer and the OpenXR app:
// display meshes of its bounded bodies, the chain of slicing hyperplanes from the slice offsets
// (x_{n-1} = w1 in the world, then x_{n-2} = w2 in that slice, ..), and the slices of the bodies in the
// final 3D frame. Half-spaces are not sliced: the first static one is the ground of the picture.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "wedge/slicing/slicer.hpp"
#include "wedge/world.hpp"

namespace wedge::slicing {

// How finely round shapes are tessellated: Fine at the constructor's subdivisions, Coarse at its
// coarse_subdivisions (a viewer's level of detail while the scene plays).
enum class Detail { Fine, Coarse };

template <int N>
class WorldSlices {
 public:
  struct Entry {
    int body = 0;          // index in the world
    BodySlicer<N> slicer;
    std::optional<BodySlicer<N>> coarse;  // only where the coarse tessellation differs (round shapes)
    double radius = 0.0;   // m, of a ball about the centre of mass holding the whole mesh (both levels)
  };

  // offsets: up to N - 3 slice offsets (missing ones are 0). subdivisions: the display tessellation of
  // round shapes; coarse_subdivisions (0: none) a second, coarser one for Detail::Coarse. Throws
  // wedge::Error "bodies[i].shape: ..." for a shape that cannot be tessellated.
  WorldSlices(const World<N>& world, const std::vector<double>& offsets, int subdivisions,
              int coarse_subdivisions = 0);

  // Moves the slice (same meaning as the constructor's offsets); the prepared meshes are kept.
  void set_offsets(const std::vector<double>& offsets);

  const std::vector<Entry>& entries() const { return entries_; }
  const Flat3<N>& flat() const { return flat_; }
  const SliceChain<N>& chain() const { return chain_; }

  // The slice of each bounded body (entries() order) in the world's current state. Bodies whose bounding
  // ball misses the flat are not sliced; `out`'s storage is reused (no allocation once it has grown, in 3D
  // and 4D).
  void slice(const World<N>& world, std::vector<DisplayMesh<3>>& out, Detail detail = Detail::Fine);

  // A ball in slice coordinates holding body k's slice (absent if the slice misses the body): the body
  // lies in the ball of `radius` about its centre, whose cut by the 3-flat is the ball of radius
  // sqrt(radius^2 - d^2) about the centre's foot point, d the centre's distance from the flat.
  std::optional<std::pair<Eigen::Vector3d, double>> slice_bound(const World<N>& world, std::size_t k) const;

  // A world vector in slice coordinates (its projection onto the 3-flat).
  Eigen::Vector3d to_slice_vector(const Vec<N>& v) const { return flat_.frame.transpose() * v; }
  // A world point in slice coordinates (its foot point on the 3-flat).
  Eigen::Vector3d to_slice_point(const Vec<N>& x) const { return flat_.frame.transpose() * (x - flat_.origin); }

  // The ground: the first static half-space {n . x <= offset}, placed by its body, cut by the flat:
  // {y : (F^T n) . y <= offset - n . origin}, normalised. Absent if there is none or it is parallel.
  std::optional<std::pair<Eigen::Vector3d, double>> ground(const World<N>& world) const;

 private:
  SliceChain<N> chain_;
  Flat3<N> flat_;
  std::vector<Entry> entries_;
  std::optional<int> ground_body_;

  // The part of x - origin normal to the 3-flat (world): its length is x's distance from the flat.
  Vec<N> off_flat(const Vec<N>& x) const;
  // True if the ball of `radius` about `center` (world) lies off the 3-flat: the body there slices to nothing.
  bool misses(const Vec<N>& center, double radius) const;
};

}  // namespace wedge::slicing
