// Backs the `dynslam` command's heap with transparent huge pages. main() calls it first thing; the
// library does not (it would change malloc for a user's whole process: Python users can set
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1 instead, docs/SOLVER.md "Page faults").
//
// A solve touches most of its memory once: the Jacobian, JᵀJ and CHOLMOD's factor are allocated
// at the first step and reused. Each 4 KiB page then costs a page fault, and on virtual machines
// such as this project's 2-core one a fault costs 8–16 µs: kitti_0003/wc faults 25 500 times,
// about a quarter of its process time (docs/SOLVER.md "Page faults"). With 2 MiB pages it faults
// 900–1 300 times. Debian's kernels give huge pages only to memory advised with MADV_HUGEPAGE
// (/sys/kernel/mm/transparent_hugepage/enabled = madvise), and glibc's malloc does not advise
// its heap unless GLIBC_TUNABLES=glibc.malloc.hugetlb=1 is set before the process starts.
//
// So this grows the heap by a reserve (untouched virtual memory: it costs no RAM until used),
// advises it, and keeps malloc in it: every block from the heap (no mmap'd chunks) and the heap's
// top never returned to the kernel. Memory beyond the reserve is ordinary pages. It does nothing
// when DYNSLAM_HUGE_PAGES=0 is set, under a sanitizer's allocator, with strict overcommit
// (vm.overcommit_memory = 2, where a reserve would be charged); when the heap cannot grow
// (e.g. ulimit -d) or the kernel refuses the advice, malloc gets its settings back (glibc's
// dynamic mmap threshold alone stays off once mallopt has been called).
#ifndef DYNSLAM_PROCESS_HUGE_PAGE_HEAP_H_
#define DYNSLAM_PROCESS_HUGE_PAGE_HEAP_H_

#include <cstddef>
#include <cstdint>
#include <string>

namespace dynslam {

// Built with a sanitizer, whose allocator replaces malloc: then the heap is left alone.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizerAllocator = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
inline constexpr bool kSanitizerAllocator = true;
#else
inline constexpr bool kSanitizerAllocator = false;
#endif
#else
inline constexpr bool kSanitizerAllocator = false;
#endif

struct HugePageHeap {
  bool advised = false;
  uintptr_t begin = 0, end = 0;  // the advised range, 2 MiB aligned, when `advised`
  std::string reason;            // why not, when not `advised`
};

// The reserve: a quarter of physical memory, at most 8 GiB, unless `reserve_bytes` is given.
HugePageHeap AdviseHugePagesForTheHeap(size_t reserve_bytes = 0);

}  // namespace dynslam

#endif  // DYNSLAM_PROCESS_HUGE_PAGE_HEAP_H_
