// RAII owners for SUNDIALS 6 objects (docs/design.md §6.2: SUNDIALS handles live behind
// RAII owners; no void* casts outside the adapters). Every object is created
// from one SUNContext; members must be declared context first, integrator
// memory last, so that destruction runs in the reverse (safe) order.
#pragma once
#include <arkode/arkode_arkstep.h>
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace wl::sun {

struct ContextDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;

inline Context make_context() {
  SUNContext c = nullptr;
  if (SUNContext_Create(nullptr, &c) != 0 || !c) throw std::runtime_error("SUNContext_Create failed");
  return Context(c);
}

inline Vector make_vector(long n, SUNContext ctx) {
  N_Vector v = N_VNew_Serial(static_cast<sunindextype>(n), ctx);
  if (!v) throw std::runtime_error("N_VNew_Serial failed");
  return Vector(v);
}

inline double* data(N_Vector v) { return N_VGetArrayPointer(v); }

// A return flag's name from ARKStepGetReturnFlagName / IDAGetReturnFlagName,
// which hand over a malloc'd string (freed here).
inline std::string flag_name(char* owned) {
  std::string s = owned ? owned : "";
  std::free(owned);
  return s;
}

// Integrator memory (IDA or ARKStep): an opaque pointer with its free function.
template <void (*Free)(void**)>
class Memory {
 public:
  Memory() = default;
  explicit Memory(void* mem) : mem_(mem) {
    if (!mem_) throw std::runtime_error("SUNDIALS integrator memory could not be created");
  }
  ~Memory() { reset(); }
  Memory(const Memory&) = delete;
  Memory& operator=(const Memory&) = delete;
  Memory(Memory&& o) noexcept : mem_(o.mem_) { o.mem_ = nullptr; }
  Memory& operator=(Memory&& o) noexcept {
    if (this != &o) {
      reset();
      mem_ = o.mem_;
      o.mem_ = nullptr;
    }
    return *this;
  }
  void reset() {
    if (mem_) Free(&mem_);
    mem_ = nullptr;
  }
  void* get() const { return mem_; }

 private:
  void* mem_ = nullptr;
};

using IdaMemory = Memory<&IDAFree>;
using ArkStepMemory = Memory<&ARKStepFree>;

// The only way callbacks recover their owner from SUNDIALS' user_data.
template <class T>
T& user_data_as(void* user_data) {
  return *static_cast<T*>(user_data);
}

}  // namespace wl::sun
