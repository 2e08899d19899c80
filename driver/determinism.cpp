#include "driver/determinism.h"

#include <dlfcn.h>

#include <cstdlib>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace wl {
namespace {

// OpenBLAS is looked up at run time: the BLAS is chosen by the system (Debian alternatives).
template <class F>
F openblas(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_DEFAULT, name));
}

}  // namespace

void hold_blas_threads() {
  if (std::getenv("OPENBLAS_NUM_THREADS")) return;
  if (const auto set = openblas<void (*)(int)>("openblas_set_num_threads")) set(1);
}

Json thread_counts() {
  Json t = Json::object();
#ifdef _OPENMP
  t.set("openmp", omp_get_max_threads());
#else
  t.set("openmp", 1);
#endif
  const auto get = openblas<int (*)()>("openblas_get_num_threads");
  t.set("openblas", get ? Json(get()) : Json());
  return t;
}

}  // namespace wl
