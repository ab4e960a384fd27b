#include "huge_page_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace dynslam {
namespace {

constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
constexpr int kGlibcDefaultMmapMax = 65536;
constexpr int kGlibcDefaultTrimThreshold = 128 * 1024;

bool StrictOvercommit() {
  std::ifstream in("/proc/sys/vm/overcommit_memory");
  int mode = 0;
  return (in >> mode) && mode == 2;
}

size_t DefaultReserve() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const size_t quarter = pages > 0 && page > 0 ? static_cast<size_t>(pages) / 4 * page : 0;
  return std::min(quarter, size_t{8} << 30);
}

HugePageHeap Not(const char* reason) {
  HugePageHeap heap;
  heap.reason = reason;
  return heap;
}

HugePageHeap RestoreMallocAndNot(const char* reason) {
  mallopt(M_MMAP_MAX, kGlibcDefaultMmapMax);
  mallopt(M_TRIM_THRESHOLD, kGlibcDefaultTrimThreshold);
  return Not(reason);
}

}  // namespace

HugePageHeap AdviseHugePagesForTheHeap(size_t reserve_bytes) {
  const char* setting = std::getenv("DYNSLAM_HUGE_PAGES");
  if (setting != nullptr && std::strcmp(setting, "0") == 0) return Not("DYNSLAM_HUGE_PAGES=0");
  if (kSanitizerAllocator) return Not("a sanitizer's allocator");
  if (StrictOvercommit()) return Not("strict overcommit (vm.overcommit_memory = 2)");
  const size_t reserve = reserve_bytes > 0 ? reserve_bytes : DefaultReserve();
  if (reserve < 2 * kHugePage) return Not("no reserve");

  mallopt(M_MMAP_MAX, 0);  // every block from the heap, so within the advised range
  const uintptr_t before = reinterpret_cast<uintptr_t>(sbrk(0));
  void* block = std::malloc(reserve);
  const uintptr_t after = reinterpret_cast<uintptr_t>(sbrk(0));
  if (block == nullptr || after < before + reserve) {  // the heap could not grow: mmap'd
    std::free(block);
    return RestoreMallocAndNot("the heap cannot grow by the reserve");
  }
  mallopt(M_TRIM_THRESHOLD, -1);  // keep the heap's top (and its advice) when blocks are freed
  // The reserve starts where the heap's old top chunk did, which may be below `before`: advise
  // from the reserve's own first 2 MiB boundary, where a later large block will start too.
  const uintptr_t first = reinterpret_cast<uintptr_t>(block);
  std::free(block);

  HugePageHeap heap;
  heap.begin = (first + kHugePage - 1) & ~(kHugePage - 1);
  heap.end = after & ~(kHugePage - 1);
  if (madvise(reinterpret_cast<void*>(heap.begin), heap.end - heap.begin, MADV_HUGEPAGE) != 0) {
    return RestoreMallocAndNot(
        "madvise(MADV_HUGEPAGE) refused (a kernel without transparent huge pages)");
  }
  heap.advised = true;
  return heap;
}

}  // namespace dynslam
