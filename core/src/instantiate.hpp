// Internal: explicit instantiation for every supported dimension, N = 2..6, in one place. A file
// defines WEDGE_INSTANTIATE(N) with its templates and writes WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE).
#pragma once

#define WEDGE_FOR_EACH_DIM(M) M(2) M(3) M(4) M(5) M(6)
