// The soft step's lane kernels (lanes.hpp) in AVX2's 4-lane packs, for 2D and 3D, whose lane counts
// 4 divides. Only these functions are compiled for AVX2 (gnu::target; soft_step.cpp calls them where
// the CPU has it). They read the 2-lane packs' storage through 4-lane types (lanes_as), so this file
// alone is compiled without type-based alias analysis (core/CMakeLists.txt).
#include "contact/lanes.hpp"

namespace wedge::contact::lanes {

#if WEDGE_AVX2_LANES
template <int N, class Kernel>
[[gnu::target("avx2")]] void run_avx2(ContactState<N>& s, const Kernel& kernel, int begin, int end) {
  kernel.template run<LaneTypes<N, 4>>(s, begin, end);
}

#define WEDGE_INSTANTIATE(N)                                                                  \
  static_assert(kWideLanes4<N>);                                                              \
  template void run_avx2<N, WidePass<N>>(ContactState<N>&, const WidePass<N>&, int, int);     \
  template void run_avx2<N, WarmStart<N>>(ContactState<N>&, const WarmStart<N>&, int, int);   \
  template void run_avx2<N, Separations<N>>(ContactState<N>&, const Separations<N>&, int, int);
WEDGE_INSTANTIATE(2)
WEDGE_INSTANTIATE(3)
#undef WEDGE_INSTANTIATE
#endif

}  // namespace wedge::contact::lanes
