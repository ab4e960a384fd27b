// The BLAS that CHOLMOD's supernodal factorisation calls, as loaded in this process (internal,
// not public API; docs/DEPENDENCIES.md "Why OpenBLAS").
//
// OpenBLAS built without threads and without USE_LOCKING (Debian 12's libopenblas0-serial)
// shares its work buffers between callers unlocked: two solves factorising in two threads at
// once corrupt each other's results. dynslam depends on Debian's libopenblas0-pthread, which
// locks them; where the process has the serial build all the same (an alternative selected by
// hand), ScopedBlasExclusion makes concurrent solves take turns instead of giving wrong answers.
// OpenBLAS's functions are looked up at run time, so that dynslam needs no OpenBLAS to build.
#ifndef DYNSLAM_SRC_BLAS_RUNTIME_H_
#define DYNSLAM_SRC_BLAS_RUNTIME_H_

#include <mutex>

namespace dynslam {

// True when the process's BLAS is an OpenBLAS built without threads (openblas_get_parallel()
// is 0): not safe for concurrent callers.
bool BlasIsUnlockedOpenBlas();

// Sets a threaded OpenBLAS's thread count (process-wide) to `threads` unless it is that already;
// does nothing for any other BLAS. A solve calls it with its own threads: a threaded OpenBLAS
// left at one thread per core and called from concurrent solves spends its time waking and
// waiting for its pool (eight concurrent synthetic solves: 96 s against 10 s at one thread,
// docs/DEPENDENCIES.md).
void UseOpenBlasThreads(int threads);

// While alive, holds a process-wide mutex if BlasIsUnlockedOpenBlas(), else nothing.
class ScopedBlasExclusion {
 public:
  ScopedBlasExclusion();
  // True when another solve held the BLAS and this one had to wait for it.
  bool waited() const { return waited_; }

 private:
  std::unique_lock<std::mutex> lock_;
  bool waited_ = false;
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_BLAS_RUNTIME_H_
