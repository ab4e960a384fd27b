// Caps the OpenMP threads that CHOLMOD may start while a solve runs (internal, not public API).
//
// SuiteSparse 5's CHOLMOD (Debian 12: libcholmod3 5.12) runs parts of its supernodal
// factorisation in `#pragma omp parallel num_threads(CHOLMOD_OMP_NUM_THREADS)` regions, a
// compile-time 4 that OMP_NUM_THREADS does not lower. On a 2-core machine the four threads wake
// and sleep on a futex at every supernode: on kitti_0003/oc_a the supernodal factorisation of the
// normal matrix takes 0.39 s with them and 0.065 s with one thread (docs/SOLVER.md). libgomp
// bounds such a region by the number of threads requested with omp_set_num_threads() when
// dynamic adjustment is on (omp_set_dynamic), so this guard turns that on with `threads` for the
// calling thread, the one Ceres factors in, and restores the settings when it goes out of scope.
// With one thread it sets the maximum of active levels to 0 instead, so that every region runs
// in the calling thread: under dynamic adjustment libgomp reads the load average (a sysinfo
// system call) at every region, thousands per factorisation, about a tenth of the linear solves'
// time on synthetic/oc_a and kitti_0003/oc_b (docs/SOLVER.md).
//
// The OpenMP runtime is the one CHOLMOD loaded; its functions are looked up at run time so that
// dynslam itself needs no OpenMP to build. Without a runtime (CHOLMOD built without OpenMP) the
// guard does nothing.
#ifndef DYNSLAM_SRC_OPENMP_THREAD_CAP_H_
#define DYNSLAM_SRC_OPENMP_THREAD_CAP_H_

namespace dynslam {

class ScopedOpenMpThreadCap {
 public:
  explicit ScopedOpenMpThreadCap(int threads);
  ~ScopedOpenMpThreadCap();
  ScopedOpenMpThreadCap(const ScopedOpenMpThreadCap&) = delete;
  ScopedOpenMpThreadCap& operator=(const ScopedOpenMpThreadCap&) = delete;

  // False when no OpenMP runtime is loaded in the process.
  bool active() const { return active_; }

 private:
  bool active_ = false;
  int saved_dynamic_ = 0;
  int saved_max_threads_ = 1;
  int saved_max_active_levels_ = 1;
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_OPENMP_THREAD_CAP_H_
