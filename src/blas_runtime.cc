#include "src/blas_runtime.h"

#include <dlfcn.h>

namespace dynslam {
namespace {

struct OpenBlas {
  int (*get_parallel)() = nullptr;
  int (*get_num_threads)() = nullptr;
  void (*set_num_threads)(int) = nullptr;
};

const OpenBlas& Runtime() {
  static const OpenBlas runtime = [] {
    OpenBlas r;
    r.get_parallel = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
    r.get_num_threads = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    r.set_num_threads =
        reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    return r;
  }();
  return runtime;
}

std::mutex& BlasMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

bool BlasIsUnlockedOpenBlas() {
  return Runtime().get_parallel != nullptr && Runtime().get_parallel() == 0;
}

void UseOpenBlasThreads(int threads) {
  const OpenBlas& blas = Runtime();
  if (blas.get_parallel == nullptr || blas.get_parallel() == 0) return;
  if (blas.get_num_threads == nullptr || blas.set_num_threads == nullptr) return;
  if (blas.get_num_threads() != threads) blas.set_num_threads(threads);
}

ScopedBlasExclusion::ScopedBlasExclusion() {
  if (!BlasIsUnlockedOpenBlas()) return;
  lock_ = std::unique_lock<std::mutex>(BlasMutex(), std::try_to_lock);
  if (lock_.owns_lock()) return;
  waited_ = true;
  lock_.lock();
}

}  // namespace dynslam
