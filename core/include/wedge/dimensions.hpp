// The dimensions Wedge is built for: every template over N is instantiated for N = 2..6, in one place.
// A library file defines WEDGE_INSTANTIATE(N) with its templates and writes
// WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE); a user's own templates over N can do the same.
#pragma once

namespace wedge {

inline constexpr int kMinDimension = 2, kMaxDimension = 6;

}  // namespace wedge

#define WEDGE_FOR_EACH_DIM(M) M(2) M(3) M(4) M(5) M(6)
