// The `dynslam` command's huge-page heap (process/huge_page_heap.h). It changes malloc for the whole
// process, so each case runs it in a child process (a death test's fork) and reports by exit code.
#include "huge_page_heap.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace dynslam {
namespace {

constexpr size_t kMiB = size_t{1} << 20;

bool KernelHasTransparentHugePages() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  return std::getline(in, modes) && modes.find("[never]") == std::string::npos;
}

// The VmFlags of the mapping of /proc/self/smaps that holds `address` ("" if none does).
std::string VmFlagsAt(uintptr_t address) {
  std::ifstream smaps("/proc/self/smaps");
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long begin = 0, end = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &begin, &end) == 2 && line.find(':') > 8) {
      inside = begin <= address && address < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "";
}

long VmDataKiB() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmData:", 0) == 0) return std::stol(line.substr(7));
  }
  return -1;
}

// Child-side checks: exit 0 when all hold, else the number of the first that failed.
void AdvisedHeapChild() {
  const HugePageHeap heap = AdviseHugePagesForTheHeap(64 * kMiB);
  if (!heap.advised) std::_Exit(1);
  if (heap.begin % (2 * kMiB) != 0 || heap.end % (2 * kMiB) != 0) std::_Exit(2);
  if (heap.end - heap.begin < 60 * kMiB) std::_Exit(3);
  if (VmFlagsAt(heap.begin).find(" hg") == std::string::npos) std::_Exit(4);  // MADV_HUGEPAGE
  // 32 MiB is far above glibc's mmap threshold (128 KiB): without the policy it would be a
  // mapping of its own, outside the advised range.
  char* block = static_cast<char*>(std::malloc(32 * kMiB));
  const auto at = reinterpret_cast<uintptr_t>(block);
  if (block == nullptr || at + 2 * kMiB < heap.begin || at + 32 * kMiB > heap.end) std::_Exit(5);
  std::memset(block, 1, 32 * kMiB);
  std::free(block);
  if (reinterpret_cast<uintptr_t>(sbrk(0)) < heap.end) std::_Exit(6);  // the top was kept
  std::_Exit(0);
}

// The same after small blocks have grown the heap until a 2 MiB boundary falls inside its top
// chunk (the free space at its end, where the reserve will start): then the reserve begins below
// the heap's end, and the advised range must begin at the reserve's first boundary, not at the
// one after the heap's end. Where the heap starts is random (ASLR); this makes the case certain.
void AdvisedHeapFromATopChunkAcrossABoundaryChild() {
  for (int i = 0;; ++i) {
    if (i == 4096) std::_Exit(7);
    const auto block = reinterpret_cast<uintptr_t>(std::malloc(4000));
    const uintptr_t top_chunk = block + 4000, heap_end = reinterpret_cast<uintptr_t>(sbrk(0));
    if (block == 0) std::_Exit(8);
    if (top_chunk / (2 * kMiB) < heap_end / (2 * kMiB)) break;
  }
  AdvisedHeapChild();
}

void HeapThatCannotGrowChild() {
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(VmDataKiB() + 16 * 1024) * 1024;
  if (setrlimit(RLIMIT_DATA, &limit) != 0) std::_Exit(10);
  const uintptr_t top = reinterpret_cast<uintptr_t>(sbrk(0));
  const HugePageHeap heap = AdviseHugePagesForTheHeap(256 * kMiB);
  if (heap.advised || heap.reason.find("cannot grow") == std::string::npos) std::_Exit(1);
  if (reinterpret_cast<uintptr_t>(sbrk(0)) > top + 2 * kMiB) std::_Exit(2);  // no reserve kept
  void* block = std::malloc(8 * kMiB);  // malloc still works within the limit
  if (block == nullptr) std::_Exit(3);
  std::free(block);
  std::_Exit(0);
}

void SwitchedOffChild() {
  setenv("DYNSLAM_HUGE_PAGES", "0", 1);
  const uintptr_t top = reinterpret_cast<uintptr_t>(sbrk(0));
  const HugePageHeap heap = AdviseHugePagesForTheHeap(64 * kMiB);
  if (heap.advised || heap.reason != "DYNSLAM_HUGE_PAGES=0") std::_Exit(1);
  if (reinterpret_cast<uintptr_t>(sbrk(0)) != top) std::_Exit(2);
  std::_Exit(0);
}

TEST(HugePageHeapTest, AdvisesTheReserveAndKeepsLargeBlocksInIt) {
  if (kSanitizerAllocator) GTEST_SKIP() << "a sanitizer's allocator replaces malloc";
  if (!KernelHasTransparentHugePages()) GTEST_SKIP() << "transparent huge pages are off";
  EXPECT_EXIT(AdvisedHeapChild(), testing::ExitedWithCode(0), "");
}

TEST(HugePageHeapTest, AdvisesFromTheReserveWhenItStartsBelowTheHeapsEnd) {
  if (kSanitizerAllocator) GTEST_SKIP() << "a sanitizer's allocator replaces malloc";
  if (!KernelHasTransparentHugePages()) GTEST_SKIP() << "transparent huge pages are off";
  EXPECT_EXIT(AdvisedHeapFromATopChunkAcrossABoundaryChild(), testing::ExitedWithCode(0), "");
}

TEST(HugePageHeapTest, FallsBackToOrdinaryMallocWhenTheHeapCannotGrow) {
  if (kSanitizerAllocator) GTEST_SKIP() << "a sanitizer's allocator replaces malloc";
  EXPECT_EXIT(HeapThatCannotGrowChild(), testing::ExitedWithCode(0), "");
}

TEST(HugePageHeapTest, DoesNothingWithDynslamHugePages0) {
  EXPECT_EXIT(SwitchedOffChild(), testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace dynslam
