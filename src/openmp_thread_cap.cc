#include "src/openmp_thread_cap.h"

#include <dlfcn.h>

namespace dynslam {
namespace {

// The six OpenMP runtime calls the cap needs (same C ABI in libgomp and LLVM's libomp).
struct OpenMpRuntime {
  void (*set_dynamic)(int) = nullptr;
  int (*get_dynamic)() = nullptr;
  void (*set_num_threads)(int) = nullptr;
  int (*get_max_threads)() = nullptr;
  void (*set_max_active_levels)(int) = nullptr;
  int (*get_max_active_levels)() = nullptr;

  bool loaded() const {
    return set_dynamic && get_dynamic && set_num_threads && get_max_threads &&
           set_max_active_levels && get_max_active_levels;
  }
};

template <typename F>
void Lookup(const char* name, F* function) {
  *function = reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}

const OpenMpRuntime& Runtime() {
  static const OpenMpRuntime runtime = [] {
    OpenMpRuntime r;
    Lookup("omp_set_dynamic", &r.set_dynamic);
    Lookup("omp_get_dynamic", &r.get_dynamic);
    Lookup("omp_set_num_threads", &r.set_num_threads);
    Lookup("omp_get_max_threads", &r.get_max_threads);
    Lookup("omp_set_max_active_levels", &r.set_max_active_levels);
    Lookup("omp_get_max_active_levels", &r.get_max_active_levels);
    return r;
  }();
  return runtime;
}

}  // namespace

ScopedOpenMpThreadCap::ScopedOpenMpThreadCap(int threads) {
  const OpenMpRuntime& omp = Runtime();
  if (!omp.loaded()) return;
  active_ = true;
  saved_dynamic_ = omp.get_dynamic();
  saved_max_threads_ = omp.get_max_threads();
  saved_max_active_levels_ = omp.get_max_active_levels();
  if (threads <= 1) {
    omp.set_max_active_levels(0);
    return;
  }
  omp.set_dynamic(1);
  omp.set_num_threads(threads);
}

ScopedOpenMpThreadCap::~ScopedOpenMpThreadCap() {
  if (!active_) return;
  const OpenMpRuntime& omp = Runtime();
  omp.set_dynamic(saved_dynamic_);
  omp.set_num_threads(saved_max_threads_);
  omp.set_max_active_levels(saved_max_active_levels_);
}

}  // namespace dynslam
