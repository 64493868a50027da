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
// Shadows: a cube above the ground darkens exactly the ground under it (the square's perspective image,
// counted the same way), less the higher it is, and nothing else. Contact sheets: size, layout, the box
// filter and the labels, without OpenGL.
// Floating-point traps (tests/main.cpp) are off wherever Mesa draws: its software rasteriser computes with
// infinities on purpose (clipping, depth), which is Mesa's arithmetic, not ours.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "fp_traps.hpp"
#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/png.hpp"
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

// An orthographic view down -z from z = 10 m, 100 pixels per metre.
FrameDesc looking_down_z() {
  FrameDesc frame;
  frame.camera.orthographic = true;
  frame.camera.ortho_height = kOrthoHeight;
  frame.camera.eye = Eigen::Vector3d(0, 0, 10);
  frame.camera.target = Eigen::Vector3d::Zero();
  frame.camera.up = Eigen::Vector3d::UnitY();
  return frame;
}

// Pixels that differ from the background (read at a corner, which the shapes never reach).
long covered_pixels(const DisplayMesh<3>& mesh) {
  const fp_traps::Suspended mesa;
  OffscreenContext ctx(kW, kH);
  Renderer renderer;
  FrameDesc frame = looking_down_z();
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

TEST_CASE("Renderer: an overlay is drawn over a body in front of it, a plain mesh is hidden", "[renderer]") {
  // Orthographic, looking down -z: a 1 m cube at the origin hides a 0.4 m cube 2 m behind it, unless that
  // one is an overlay. Only the small cube is green; the big one red. The overlay's square: 40 x 40 px.
  MeshSlicer<4> slicer(display_mesh(Shape<4>::box(Vec<4>::Constant(0.5)), 1));
  const DisplayMesh<3> front = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(0.0));
  MeshSlicer<4> small_slicer(display_mesh(Shape<4>::box(Vec<4>::Constant(0.2)), 1));
  const DisplayMesh<3> back = small_slicer.slice(Placement<4>{Mat<4>::Identity(), Vec<4>(0, 0, -2, 0)},
                                                 Hyperplane<4>::axis(0.0));
  for (const bool overlay : {false, true}) {
    const fp_traps::Suspended mesa;
    OffscreenContext ctx(kW, kH);
    Renderer renderer;
    FrameDesc frame = looking_down_z();
    frame.meshes.push_back({&back, Color{0.1f, 0.9f, 0.1f}, overlay});
    frame.meshes.push_back({&front, Color{0.9f, 0.1f, 0.1f}});
    renderer.draw(frame, kW, kH);
    const std::vector<std::uint8_t> px = ctx.read_rgba();
    long green = 0;
    for (std::size_t i = 0; i < px.size(); i += 4) green += px[i + 1] > 2 * px[i] + 30 ? 1 : 0;
    INFO("overlay " << overlay << ": " << green << " green px");
    const double side = 0.4 * kPixelsPerMetre;
    if (overlay)
      CHECK(std::abs(double(green) - side * side) <= 4 * side + 4);
    else
      CHECK(green == 0);
  }
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
  const fp_traps::Suspended mesa;
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

namespace {

// Where a point lands in the picture: pixel coordinates from the top-left corner (pixel centres at +0.5).
Eigen::Vector2d to_pixel(const Camera& camera, const Eigen::Vector3d& p, int w, int h) {
  const Eigen::Vector4d clip = camera.projection(double(w) / h) * camera.view() * p.homogeneous();
  return {(clip.x() / clip.w() + 1) / 2 * w, (1 - clip.y() / clip.w()) / 2 * h};
}

bool inside_convex(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
  int sign = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    const double c = (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();
    const int s = c > 0 ? 1 : (c < 0 ? -1 : 0);
    if (s != 0 && sign != 0 && s != sign) return false;
    if (s != 0) sign = s;
  }
  return true;
}

}  // namespace

TEST_CASE("Renderer: a body's shadow darkens the ground straight below it, and nothing else", "[renderer]") {
  constexpr int w = 240, h = 180;
  const fp_traps::Suspended mesa;
  OffscreenContext ctx(w, h);
  Renderer renderer;
  MeshSlicer<4> slicer(display_mesh(Shape<4>::box(Vec<4>::Constant(0.5)), 1));
  const DisplayMesh<3> unit_cube = slicer.slice(Placement<4>{}, Hyperplane<4>::axis(0.0));
  auto lifted = [&](double height) {  // the cube with its bottom `height` above the ground y = 0
    DisplayMesh<3> m = unit_cube;
    for (Vec<3>& v : m.vertices) v.y() += 0.5 + height;
    return m;
  };
  FrameDesc frame;
  frame.camera.eye = Eigen::Vector3d(0.3, 6, 6);
  frame.camera.target = Eigen::Vector3d(0, 1, 0);
  frame.ground.enabled = true;
  frame.ground.spacing = 0.7;
  auto draw = [&](const DisplayMesh<3>& mesh, bool shadows) {
    frame.meshes = {{&mesh, Color{0.2f, 0.4f, 0.9f}}};
    frame.ground.shadows = shadows;
    renderer.draw(frame, w, h);
    return ctx.read_rgba();
  };
  const DisplayMesh<3> cube = lifted(2.0);
  const std::vector<std::uint8_t> lit = draw(cube, false), shaded = draw(cube, true);

  // The shadow: the unit square at the origin, seen in perspective (the cube does not hide it from here).
  std::vector<Eigen::Vector2d> square;
  for (const auto& [x, z] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}})
    square.push_back(to_pixel(frame.camera, Eigen::Vector3d(x, 0, z), w, h));
  double area = 0, perimeter = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d a = square[i], b = square[(i + 1) % 4];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    perimeter += (b - a).norm();
  }
  area = std::abs(area);
  REQUIRE(area > 200);  // a fair test: hundreds of pixels
  long darker = 0, brighter = 0, outside = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (std::size_t(y) * w + std::size_t(x)) * 4;
      if (lit[i] == shaded[i] && lit[i + 1] == shaded[i + 1] && lit[i + 2] == shaded[i + 2]) continue;
      const bool dark = shaded[i] < lit[i] && shaded[i + 1] < lit[i + 1] && shaded[i + 2] < lit[i + 2];
      (dark ? darker : brighter) += 1;
      // Allow the pixels the square's edge passes through: test the centre moved half a pixel inward.
      const Eigen::Vector2d c(x + 0.5, y + 0.5), mid = (square[0] + square[2]) / 2;
      const Eigen::Vector2d inward = c + 0.75 * (mid - c).normalized();
      outside += inside_convex(square, inward) ? 0 : 1;
    }
  INFO(darker << " darker pixels, " << brighter << " brighter, " << outside << " outside; square " << area << " px^2");
  CHECK(brighter == 0);
  CHECK(outside == 0);
  CHECK(std::abs(double(darker) - area) <= perimeter + 4);

  // Under the middle: clearly darker; darker still for a body just above the ground, lighter high up.
  const Eigen::Vector2d centre = to_pixel(frame.camera, Eigen::Vector3d::Zero(), w, h);
  const std::size_t at = (std::size_t(centre.y()) * w + std::size_t(centre.x())) * 4;
  const DisplayMesh<3> low = lifted(0.01), high = lifted(8.0);
  const int near_ground = draw(low, true)[at + 1], high_up = draw(high, true)[at + 1];
  INFO("green at the centre: lit " << int(lit[at + 1]) << ", 2 m up " << int(shaded[at + 1]) << ", 0.01 m up "
                                   << near_ground << ", 8 m up " << high_up);
  CHECK(shaded[at + 1] < 0.85 * lit[at + 1]);
  CHECK(near_ground < shaded[at + 1]);
  CHECK(high_up > shaded[at + 1]);
  CHECK(high_up < lit[at + 1]);
}

TEST_CASE("ContactSheet: a grid of box-filtered tiles with labels", "[renderer][sheet]") {
  // 5 tiles, 4 to a row: 2 rows; 4 px borders.
  ContactSheet sheet(5, 4, 8, 6);
  CHECK(sheet.width() == 4 + 4 * (8 + 4));
  CHECK(sheet.height() == 4 + 2 * (6 + 4));
  REQUIRE(sheet.rgba().size() == std::size_t(sheet.width() * sheet.height() * 4));
  auto pixel = [&](int x, int y) {
    const std::size_t i = (std::size_t(y) * std::size_t(sheet.width()) + std::size_t(x)) * 4;
    return std::array<int, 4>{sheet.rgba()[i], sheet.rgba()[i + 1], sheet.rgba()[i + 2], sheet.rgba()[i + 3]};
  };
  // Tile 4 (second row, first column) from a 16 x 12 checkerboard of black and white pixels: every
  // output pixel averages a 2 x 2 block, half white, so it is mid grey (rounded half up).
  std::vector<std::uint8_t> checker(16 * 12 * 4);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) checker[std::size_t((y * 16 + x) * 4 + c)] = c == 3 || (x + y) % 2 ? 255 : 0;
  sheet.place(4, checker, 16, 12);
  CHECK(sheet.tile_x(4) == 4);
  CHECK(sheet.tile_y(4) == 4 + 6 + 4);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) REQUIRE(pixel(4 + x, 14 + y) == std::array<int, 4>{128, 128, 128, 255});
  // Tile 1 from a solid red picture; the border and the unplaced tiles stay dark grey.
  std::vector<std::uint8_t> red(40 * 30 * 4, 0);
  for (std::size_t i = 0; i < red.size(); i += 4) red[i] = 255, red[i + 3] = 255;
  sheet.place(1, red, 40, 30);
  CHECK(pixel(sheet.tile_x(1), sheet.tile_y(1)) == std::array<int, 4>{255, 0, 0, 255});
  CHECK(pixel(sheet.tile_x(1) + 7, sheet.tile_y(1) + 5) == std::array<int, 4>{255, 0, 0, 255});
  CHECK(pixel(sheet.tile_x(1) - 1, sheet.tile_y(1)) == std::array<int, 4>{40, 40, 40, 255});
  CHECK(pixel(sheet.tile_x(0), sheet.tile_y(0)) == std::array<int, 4>{40, 40, 40, 255});
  // A label: white glyph pixels on a dark box in the tile's top-left corner ("1" has its stem at column 2).
  ContactSheet labelled(1, 4, 100, 40);
  std::vector<std::uint8_t> big_red(200 * 80 * 4, 0);
  for (std::size_t i = 0; i < big_red.size(); i += 4) big_red[i] = 255, big_red[i + 3] = 255;
  labelled.place(0, big_red, 200, 80, "t=1.50 s");
  const auto& px = labelled.rgba();
  auto at = [&](int x, int y) {
    return int(px[(std::size_t(y) * std::size_t(labelled.width()) + std::size_t(x)) * 4 + 1]);
  };
  long white = 0;
  for (int y = 4; y < 4 + 13; ++y)
    for (int x = 4; x < 4 + 6 * 8 + 5; ++x) white += at(x, y) == 255 ? 1 : 0;
  CHECK(white > 40);
  CHECK(at(4 + 3 + 12 + 2, 4 + 3 + 3) == 255);  // the third glyph, '1': its stem
  CHECK(at(4 + 99, 4 + 39) == 0);               // the red picture elsewhere (green 0)
}

TEST_CASE("downscale_rgba and write_png reject bad sizes", "[renderer][sheet]") {
  const std::vector<std::uint8_t> px(4 * 4 * 4, 7);
  CHECK_THROWS_AS(downscale_rgba(px, 4, 4, 8, 2), wedge::Error);
  CHECK_THROWS_AS(downscale_rgba(px, 4, 3, 2, 2), wedge::Error);
  CHECK(downscale_rgba(px, 4, 4, 3, 1) == std::vector<std::uint8_t>(3 * 4, 7));
  CHECK_THROWS_AS(write_png("/nonexistent-folder/x.png", px, 4, 4), wedge::Error);
}

TEST_CASE("Camera: a headset eye's asymmetric frustum puts its four edge directions on the clip box's edges",
          "[renderer]") {
  render::Camera c;
  c.eye = Eigen::Vector3d(0.3, 1.6, 0.2);
  c.target = c.eye + Eigen::Vector3d(0, 0, -1);  // looking down -z, y up: view axes = world axes
  const double left = std::tan(-0.8), right = std::tan(0.7), down = std::tan(-0.9), up = std::tan(0.6);
  c.frustum = std::array<double, 4>{left, right, down, up};
  const Eigen::Matrix4d m = c.projection(123.0) * c.view();  // (the aspect is ignored with a frustum)
  auto ndc = [&](double tx, double ty, double depth) {
    const Eigen::Vector4d p = m * Eigen::Vector4d(c.eye.x() + tx * depth, c.eye.y() + ty * depth, c.eye.z() - depth, 1.0);
    return Eigen::Vector3d(p.x() / p.w(), p.y() / p.w(), p.z() / p.w());
  };
  for (double depth : {0.5, 3.0, 40.0}) {
    CHECK(ndc(left, 0.0, depth).x() == Approx(-1.0));
    CHECK(ndc(right, 0.0, depth).x() == Approx(1.0));
    CHECK(ndc(0.0, down, depth).y() == Approx(-1.0));
    CHECK(ndc(0.0, up, depth).y() == Approx(1.0));
  }
  CHECK(ndc(0, 0, c.near_plane).z() == Approx(-1.0));
  CHECK(ndc(0, 0, c.far_plane).z() == Approx(1.0));
}
