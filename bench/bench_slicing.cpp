// Slicing and rendering timings (see bench/README.md, "Slicing and rendering"):
//   BM_SliceBall4D/S      MeshSlicer<4>::slice of a 4-ball display mesh at subdivision S (8 S^3 * 6
//                         tetrahedra), rotated, cut at w = 0.3; items = tetrahedra processed (cut or not)
//   BM_SliceBall4DMiss/S  the same with a plane that misses the ball (distances and classification only)
//   BM_SliceTesseract4D/S the same for a tesseract's mesh (flat normals)
//   BM_SliceDefaultScene  slicing the three bodies of scenes/default.json (display level 8) at w = 0,
//                         with every body moved into the slice (the duocylinder sits at w = 1.5 in the
//                         file, outside the w = 0 slice), in the pose of the scene after 0.5 s
//   BM_RenderDefaultScene slicing plus drawing that scene offscreen (OSMesa llvmpipe) at 1280x720, and
//                         reading the pixels back: one frame of `wedge render`, without the PNG encoding
//   BM_EncodePng          libpng encoding of one 1280x720 frame (the rest of `wedge render`'s per-frame work)
// One thread throughout (llvmpipe is told LP_NUM_THREADS=1 unless it is set).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/render/offscreen_context.hpp"
#include "wedge/render/png.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/shape.hpp"
#include "wedge/slicing/slicer.hpp"

namespace {

using namespace wedge;
using namespace wedge::slicing;

Placement<4> tumbled() {
  Bivector<4> b;
  for (int i = 0; i < 6; ++i) b[i] = 0.3 + 0.17 * i;
  return Placement<4>{to_matrix(wedge::exp(b)), Vec<4>(0.05, -0.02, 0.03, 0.0)};
}

void slice_mesh(benchmark::State& state, const DisplayMesh<4>& mesh, double w = 0.3) {
  MeshSlicer<4> slicer(mesh);
  DisplayMesh<3> out;
  const Placement<4> pl = tumbled();
  const Hyperplane<4> plane = Hyperplane<4>::axis(w);
  for (auto _ : state) {
    slicer.slice(pl, plane, out);
    benchmark::DoNotOptimize(out.cells.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(slicer.cell_count()));
  state.counters["tetrahedra"] = double(slicer.cell_count());
  state.counters["triangles_out"] = double(out.cells.size());
}

void BM_SliceBall4D(benchmark::State& state) {
  slice_mesh(state, display_mesh(Shape<4>::ball(1.0), int(state.range(0))));
}
BENCHMARK(BM_SliceBall4D)->Arg(8)->Arg(24)->Unit(benchmark::kMicrosecond);

// The same mesh with a plane that misses it: signed distances and classification alone.
void BM_SliceBall4DMiss(benchmark::State& state) {
  slice_mesh(state, display_mesh(Shape<4>::ball(1.0), int(state.range(0))), 2.0);
}
BENCHMARK(BM_SliceBall4DMiss)->Arg(24)->Unit(benchmark::kMicrosecond);

void BM_SliceTesseract4D(benchmark::State& state) {
  slice_mesh(state, display_mesh(Shape<4>::box(Vec<4>::Constant(0.5)), int(state.range(0))));
}
BENCHMARK(BM_SliceTesseract4D)->Arg(16)->Unit(benchmark::kMicrosecond);

// scenes/default.json's bodies, all moved into the w = 0 slice, in tumbled poses.
struct DefaultScene {
  std::vector<BodySlicer<4>> slicers;
  std::vector<Placement<4>> poses;
  std::vector<DisplayMesh<3>> slices;
  DefaultScene() {
    const int sub = 8;  // wedge render's default display level in 4D
    slicers.emplace_back(display_mesh(Shape<4>::box(Vec<4>::Constant(0.5)), sub));
    slicers.emplace_back(display_mesh(Shape<4>::box(Vec<4>(0.55, 0.15, 1.25, 0.35)), sub));
    slicers.emplace_back(display_mesh(Shape<4>::duocylinder(0.6, 0.4), sub));
    const Vec<4> at[3] = {Vec<4>(-2.0, 3.5, 0.0, 0.1), Vec<4>(2.0, 3.0, 0.0, -0.05), Vec<4>(0.0, 2.8, 0.0, 0.1)};
    for (int i = 0; i < 3; ++i) {
      Bivector<4> b;
      for (int k = 0; k < 6; ++k) b[k] = 0.2 * (i + 1) + 0.11 * k;
      poses.push_back(Placement<4>{to_matrix(wedge::exp(b)), at[i]});
    }
    slices.resize(3);
  }
  void slice() {
    const SliceChain<4> chain = SliceChain<4>::axes({0.0});
    for (std::size_t i = 0; i < slicers.size(); ++i) slices[i] = slicers[i].slice(poses[i], chain);
  }
  // The current slices seen from above and in front, over a ground grid.
  render::FrameDesc frame() const {
    render::FrameDesc f;
    f.camera.eye = Eigen::Vector3d(3.0, 5.5, 8.5);
    f.camera.target = Eigen::Vector3d(0.0, 3.0, 0.0);
    f.ground.enabled = true;
    f.ground.offset = 1.5;
    for (std::size_t i = 0; i < slices.size(); ++i) f.meshes.push_back({&slices[i], render::palette_color(int(i))});
    return f;
  }
};

void BM_SliceDefaultScene(benchmark::State& state) {
  DefaultScene scene;
  for (auto _ : state) {
    scene.slice();
    benchmark::DoNotOptimize(scene.slices.data());
  }
  std::size_t tris = 0;
  for (const auto& s : scene.slices) tris += s.cells.size();
  state.counters["triangles"] = double(tris);
}
BENCHMARK(BM_SliceDefaultScene)->Unit(benchmark::kMicrosecond);

void BM_RenderDefaultScene(benchmark::State& state) {
  ::setenv("LP_NUM_THREADS", "1", 0);
  DefaultScene scene;
  render::OffscreenContext context(1280, 720);
  render::Renderer renderer;
  for (auto _ : state) {
    scene.slice();
    renderer.draw(scene.frame(), 1280, 720);
    const std::vector<std::uint8_t> px = context.read_rgba();
    benchmark::DoNotOptimize(px.data());
  }
}
BENCHMARK(BM_RenderDefaultScene)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodePng(benchmark::State& state) {
  ::setenv("LP_NUM_THREADS", "1", 0);
  DefaultScene scene;
  scene.slice();
  render::OffscreenContext context(1280, 720);
  render::Renderer renderer;
  renderer.draw(scene.frame(), 1280, 720);
  const std::vector<std::uint8_t> px = context.read_rgba();
  const std::string path = (std::filesystem::temp_directory_path() / "wedge_bench_frame.png").string();
  for (auto _ : state) render::write_png(path, px, 1280, 720);
  std::filesystem::remove(path);
}
BENCHMARK(BM_EncodePng)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
