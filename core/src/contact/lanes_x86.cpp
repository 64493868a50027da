// The soft step's lane kernels (lanes.hpp) in 4-lane packs for x86's wider vector units, for 2D and 3D,
// whose lane counts 4 divides: once for AVX2 and once for AVX-512 (its 256-bit forms, VL). The two
// differ only in registers: AVX-512 has 32, and a pass keeps both bodies' velocities and a point's terms
// in them (in 3D twelve packs of velocities alone), where AVX2's 16 spill to the stack. Wider packs
// (8 lanes in 2D) measured slower. Only these functions are compiled for AVX (gnu::target; soft_step.cpp
// calls them where the CPU has it). They read the 2-lane packs' storage through 4-lane types (lanes_as),
// so this file alone is compiled without type-based alias analysis (core/CMakeLists.txt).
#include "contact/lanes.hpp"

namespace wedge::contact::lanes {

#if WEDGE_X86_LANES
template <int N, class Kernel>
[[gnu::target("avx2")]] void run_avx2(ContactState<N>& s, const Kernel& kernel, int begin, int end) {
  kernel.template run<LaneTypes<N, 4>>(s, begin, end);
}
template <int N, class Kernel>
[[gnu::target(WEDGE_AVX512_TARGET)]] void run_avx512(ContactState<N>& s, const Kernel& kernel, int begin,
                                                     int end) {
  kernel.template run<LaneTypes<N, 4>>(s, begin, end);
}

#define WEDGE_INSTANTIATE_KERNEL(N, KERNEL)                                                   \
  template void run_avx2<N, KERNEL<N>>(ContactState<N>&, const KERNEL<N>&, int, int);         \
  template void run_avx512<N, KERNEL<N>>(ContactState<N>&, const KERNEL<N>&, int, int);
#define WEDGE_INSTANTIATE(N)                  \
  static_assert(kWideLanes4<N>);              \
  WEDGE_INSTANTIATE_KERNEL(N, WidePass)       \
  WEDGE_INSTANTIATE_KERNEL(N, WarmStart)
WEDGE_INSTANTIATE(2)
WEDGE_INSTANTIATE(3)
#undef WEDGE_INSTANTIATE
#undef WEDGE_INSTANTIATE_KERNEL
#endif

}  // namespace wedge::contact::lanes
