// Bitwise reproducible runs (README: reproducibility). The assembly's result does
// not depend on the OpenMP thread count (graph-coloured, each entry summed in a
// fixed order, docs/design.md §3.3), but OpenBLAS, under UMFPACK's dense fronts,
// rounds differently with 1 and 2 threads. So runs hold OpenBLAS at one thread
// unless OPENBLAS_NUM_THREADS asks otherwise, and every summary records the
// thread counts in force.
#pragma once
#include "output/json_writer.h"

namespace wl {

// Sets OpenBLAS to one thread when OPENBLAS_NUM_THREADS is unset; a no-op under another BLAS.
void hold_blas_threads();
// {"openmp": n, "openblas": n (null under another BLAS)}: the thread counts in force.
Json thread_counts();

}  // namespace wl
