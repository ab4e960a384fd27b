#include "inline_openmp_regions.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace dynslam {
namespace {

using RegionBody = void (*)(void*);
using ParallelEntry = void (*)(RegionBody, void*, unsigned, unsigned);

std::atomic<bool> inlining{false};
std::atomic<uint64_t> inlined_regions{0};

// libgomp's own entry point and the four queries that tell whether it would run a team of one.
// Looked up on the first region, when the runtime that compiled the caller is loaded.
struct Libgomp {
  ParallelEntry parallel = nullptr;
  int (*get_level)() = nullptr;
  int (*get_max_active_levels)() = nullptr;
  int (*get_max_threads)() = nullptr;
  int (*get_thread_limit)() = nullptr;

  bool answers_queries() const {
    return get_level && get_max_active_levels && get_max_threads && get_thread_limit;
  }
};

template <typename F>
void Lookup(void* handle, const char* name, F* function) {
  *function = reinterpret_cast<F>(dlsym(handle, name));
}

const Libgomp& Runtime() {
  static const Libgomp runtime = [] {
    Libgomp r;
    Lookup(RTLD_NEXT, "GOMP_parallel", &r.parallel);
    Lookup(RTLD_DEFAULT, "omp_get_level", &r.get_level);
    Lookup(RTLD_DEFAULT, "omp_get_max_active_levels", &r.get_max_active_levels);
    Lookup(RTLD_DEFAULT, "omp_get_max_threads", &r.get_max_threads);
    Lookup(RTLD_DEFAULT, "omp_get_thread_limit", &r.get_thread_limit);
    return r;
  }();
  return runtime;
}

// Whether libgomp would run this region with one thread, outside any other region. `requested`
// is the num_threads clause (1 when an `if` clause is false), 0 without one.
bool TeamOfOne(const Libgomp& omp, unsigned requested) {
  if (!omp.answers_queries() || omp.get_level() != 0) return false;
  return requested == 1 || omp.get_max_active_levels() == 0 || omp.get_thread_limit() == 1 ||
         (requested == 0 && omp.get_max_threads() == 1);
}

}  // namespace

bool InlineOneThreadOpenMpRegions() {
  const char* setting = std::getenv("DYNSLAM_INLINE_OPENMP");
  const bool on = setting == nullptr || std::strcmp(setting, "0") != 0;
  inlining.store(on, std::memory_order_relaxed);
  return on;
}

void StopInliningOpenMpRegions() { inlining.store(false, std::memory_order_relaxed); }

uint64_t InlinedOpenMpRegions() { return inlined_regions.load(std::memory_order_relaxed); }

}  // namespace dynslam

// GCC's call for `#pragma omp parallel` (libgomp's ABI since GCC 4.9): `body(data)` on each thread
// of a team of `num_threads` (0: the runtime's choice), `flags` the proc_bind clause.
extern "C" void GOMP_parallel(dynslam::RegionBody body, void* data, unsigned num_threads,
                              unsigned flags) {
  const dynslam::Libgomp& omp = dynslam::Runtime();
  if (omp.parallel == nullptr ||
      (dynslam::inlining.load(std::memory_order_relaxed) && dynslam::TeamOfOne(omp, num_threads))) {
    // No runtime behind us (nothing compiled for one can be calling, but a team of one is always
    // a valid way to run a region), or the team libgomp would form has one thread.
    dynslam::inlined_regions.fetch_add(1, std::memory_order_relaxed);
    body(data);
    return;
  }
  omp.parallel(body, data, num_threads, flags);
}
