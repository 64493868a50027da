// The offscreen renderer (wedge/render/*) drawing known slices with an orthographic camera looking down
// -z: the number of pixels that differ from the background must match the analytic projected area.
//  * the w = 0 slice of a tesseract of side s is an s x s square;
//  * a rotated tesseract's slice is a convex polyhedron whose silhouette is the convex hull of its
//    projected vertices (area by the shoelace formula over a monotone-chain hull, computed here);
//  * a 4-ball's slice lies between the spheres of radii rho_in and rho (see test_slicer.cpp), so the disk's
//    area lies between pi rho_in^2 and pi rho^2.
// Tolerance: rasterisation decides each pixel on the silhouette by its centre, so only pixels the
// boundary passes through can go either way: the count may be off by at most the boundary's length in
// pixels (the perimeter at the pixel scale, plus 4 for the corners).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/slicing/slicer.hpp"
#include "slice_checks.hpp"
#include "test_util.hpp"

namespace {

using namespace wedge;
using namespace wedge::slicing;
using namespace wedge::render;

constexpr int kW = 320, kH = 240;
constexpr double kOrthoHeight = 2.4;                 // m: 100 pixels per metre
constexpr double kPixelsPerMetre = kH / kOrthoHeight;

// Pixels that differ from the background (read at a corner, which the shapes never reach).
long covered_pixels(const DisplayMesh<3>& mesh) {
  OffscreenContext ctx(kW, kH);
  Renderer renderer;
  FrameDesc frame;
  frame.camera.orthographic = true;
  frame.camera.ortho_height = kOrthoHeight;
  frame.camera.eye = Eigen::Vector3d(0, 0, 10);
  frame.camera.target = Eigen::Vector3d::Zero();
  frame.camera.up = Eigen::Vector3d::UnitY();
  frame.meshes.push_back({&mesh, Color{0.8f, 0.2f, 0.2f}});
  renderer.draw(frame, kW, kH);
  const std::vector<std::uint8_t> px = ctx.read_rgba();
  REQUIRE(px.size() == std::size_t(kW * kH * 4));
  long count = 0;
  for (std::size_t i = 0; i < px.size(); i += 4)
    count += (px[i] != px[0] || px[i + 1] != px[1] || px[i + 2] != px[2]) ? 1 : 0;
  return count;
}

// Convex hull area and perimeter of points in the plane (Andrew's monotone chain).
std::pair<double, double> hull_area_perimeter(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  double area = 0, perim = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Eigen::Vector2d& a = h[i];
    const Eigen::Vector2d& b = h[(i + 1) % h.size()];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    perim += (b - a).norm();
  }
  return {area, perim};
}

}  // namespace

TEST_CASE("Renderer: a sliced tesseract covers its square's area in pixels", "[renderer]") {
  const double s = 1.0;
  MeshSlicer<4> slicer(display_mesh(Shape<4>::box(Vec<4>::Constant(s / 2)), 1));
  const DisplayMesh<3> cube = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(0.0));
  const double side_px = s * kPixelsPerMetre;
  const long count = covered_pixels(cube);
  CHECK(std::abs(double(count) - side_px * side_px) <= 4 * side_px + 4);
}

TEST_CASE("Renderer: a rotated tesseract's slice covers its projected convex hull", "[renderer]") {
  std::mt19937_64 rng(99);
  MeshSlicer<4> slicer(display_mesh(Shape<4>::box(Vec<4>(0.5, 0.4, 0.6, 0.45)), 1));
  for (int trial = 0; trial < 5; ++trial) {
    const Placement<4> pl{to_matrix(wedge::exp(random_bivector<4>(rng, 1.5))), Vec<4>::Zero()};
    const DisplayMesh<3> cut = slicer.slice(pl, Hyperplane<4>::axis(0.1));
    REQUIRE(!cut.empty());
    std::vector<Eigen::Vector2d> pts;
    for (const Vec<3>& v : cut.vertices) pts.push_back(v.head<2>() * kPixelsPerMetre);
    const auto [area, perimeter] = hull_area_perimeter(pts);
    const long count = covered_pixels(cut);
    INFO("trial " << trial << ": " << count << " pixels, hull " << area << " px^2, perimeter " << perimeter);
    CHECK(std::abs(double(count) - area) <= perimeter + 4);
  }
}

TEST_CASE("Renderer: a sliced 4-ball covers a disk between its inner and outer radius", "[renderer]") {
  const double r = 0.9, w = 0.35;
  const int sub = 8;
  const Shape<4> ball = Shape<4>::ball(r);
  // The body lies between the balls of radius r_in and r (see test_slicer.cpp).
  const double r_in = slice_checks::inner_radius<4>(boundary_mesh<4>(ball, sub));
  const double rho = std::sqrt(r * r - w * w) * kPixelsPerMetre;
  const double rho_in = std::sqrt(r_in * r_in - w * w) * kPixelsPerMetre;
  MeshSlicer<4> slicer(display_mesh(ball, sub));
  const long count = covered_pixels(slicer.slice(Placement<4>{}, Hyperplane<4>::axis(w)));
  INFO(count << " pixels; disks " << M_PI * rho_in * rho_in << " .. " << M_PI * rho * rho);
  CHECK(double(count) <= M_PI * rho * rho + 2 * M_PI * rho + 4);
  CHECK(double(count) >= M_PI * rho_in * rho_in - 2 * M_PI * rho - 4);
  // A slice that misses the ball draws nothing.
  CHECK(covered_pixels(slicer.slice(Placement<4>{}, Hyperplane<4>::axis(1.2 * r))) == 0);
}

TEST_CASE("Renderer: the ground grid and the camera's view of it", "[renderer]") {
  // Looking straight down at a ground plane y = 0 that fills the view: every pixel is ground, none is
  // background; with the ground off, every pixel is background.
  OffscreenContext ctx(64, 48);
  Renderer renderer;
  FrameDesc frame;
  frame.camera.eye = Eigen::Vector3d(0, 5, 0);
  frame.camera.target = Eigen::Vector3d::Zero();
  frame.camera.up = Eigen::Vector3d::UnitZ();
  frame.ground.enabled = true;
  renderer.draw(frame, 64, 48);
  const std::vector<std::uint8_t> with = ctx.read_rgba();
  frame.ground.enabled = false;
  renderer.draw(frame, 64, 48);
  const std::vector<std::uint8_t> without = ctx.read_rgba();
  long differ = 0;
  for (std::size_t i = 0; i < with.size(); i += 4) differ += with[i] != without[i] ? 1 : 0;
  CHECK(differ == 64 * 48);
  for (std::size_t i = 0; i < without.size(); i += 4) REQUIRE(without[i] == without[0]);
}
