// Runs the OpenMP parallel regions that would get a team of one thread as plain calls, in the
// `dynslam` command and the benchmarks that time its solves and factorisations. Their main() calls
// InlineOneThreadOpenMpRegions(); the library does not (see below).
//
// CHOLMOD's supernodal factorisation (Debian 12: libcholmod3, built with OpenMP) enters a
// `#pragma omp parallel` region for each of its supernodes: about 5 800 per factorisation of
// parking-garage's normal matrix. A solve caps those regions to one thread
// (src/openmp_thread_cap.h), yet libgomp still sets up a team for each and ends it with a futex
// system call, a few microseconds apiece on a virtual machine: on parking-garage more than half of
// the linear solve's time (docs/SOLVER.md "OpenMP regions of one thread").
//
// The command therefore defines GCC's entry point for a parallel region, `GOMP_parallel`, itself
// (the executable's definition comes before libgomp's for every library in the process) and calls
// the region's body directly when libgomp would run it with one thread at the outermost level:
// the maximum of active levels is 0 (the one-thread cap), the region asks for one thread, or the
// process may have only one. Any other region goes to libgomp's GOMP_parallel unchanged. Inside an
// inlined body omp_get_thread_num() is 0 and omp_get_num_threads() 1, as in a team of one; only
// omp_get_level() tells the two apart (0 instead of 1). A correct OpenMP program cannot depend on
// getting more than one thread, and CHOLMOD asks the runtime for nothing but those two numbers.
//
// It replaces a symbol of the OpenMP runtime for the whole process, which a library must not do to
// its users' programs: a program or Python session that links the library keeps libgomp's regions.
// DYNSLAM_INLINE_OPENMP=0 in the environment turns it off.
#ifndef DYNSLAM_PROCESS_INLINE_OPENMP_REGIONS_H_
#define DYNSLAM_PROCESS_INLINE_OPENMP_REGIONS_H_

#include <cstdint>

namespace dynslam {

// Turns the inlining on unless DYNSLAM_INLINE_OPENMP=0 is set; returns whether it is on.
bool InlineOneThreadOpenMpRegions();

// Turns it off again (tests).
void StopInliningOpenMpRegions();

// How many regions have been run inline in this process.
uint64_t InlinedOpenMpRegions();

}  // namespace dynslam

#endif  // DYNSLAM_PROCESS_INLINE_OPENMP_REGIONS_H_
