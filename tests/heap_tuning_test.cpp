// tune_heap_for_simulation (cli/heap_tuning.h): the heap is extended once and advised to use
// transparent huge pages, so a run's first touches of its heap fault a 2 MB page at a time.
#include "tests/support/sanitizers.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/heap_tuning.h"

namespace lcs {
namespace {

bool transparent_huge_pages_possible() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  return std::getline(in, modes) && modes.find("[never]") == std::string::npos;
}

// The largest [heap] mapping whose VmFlags carry "hg" (MADV_HUGEPAGE), in bytes.
long advised_heap_bytes() {
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  long size = 0, best = 0;
  bool heap = false;
  while (std::getline(smaps, line)) {
    unsigned long from = 0, to = 0;
    char dash = 0;
    std::istringstream head(line);
    if (line.find('-') != std::string::npos && (head >> std::hex >> from >> dash >> to) && dash == '-') {
      heap = line.find("[heap]") != std::string::npos;
      size = static_cast<long>(to - from);
    } else if (heap && line.rfind("VmFlags:", 0) == 0 && (line + " ").find(" hg ") != std::string::npos) {
      best = std::max(best, size);
    }
  }
  return best;
}

TEST(HeapTuning, HeapIsAdvisedToUseHugePages) {
#if !defined(__GLIBC__) || !defined(__linux__) || LCS_UNDER_ASAN
  GTEST_SKIP() << "glibc's own heap on Linux only (AddressSanitizer has its own allocator)";
#endif
  if (!transparent_huge_pages_possible()) GTEST_SKIP() << "transparent huge pages are off on this machine";
  ASSERT_EQ(advised_heap_bytes(), 0) << "advised before the call";
  tune_heap_for_simulation();
  EXPECT_GE(advised_heap_bytes(), 32L << 20);  // most of the 64 MB reserve
  void* block = std::malloc(8 << 20);  // below the mmap threshold: from the advised heap
  ASSERT_NE(block, nullptr);
  std::free(block);
}

}  // namespace
}  // namespace lcs
