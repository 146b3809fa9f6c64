// tune_heap_for_simulation (cli/heap_tuning.h): the heap is extended once and advised to use
// transparent huge pages, so a run's first touches of its heap fault a 2 MB page at a time.
#include "tests/support/sanitizers.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/resource.h>

#include <gtest/gtest.h>

#include "cli/heap_tuning.h"
#include "tests/cli_support.h"

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
  rlimit address_space{}, data{};
  if (getrlimit(RLIMIT_AS, &address_space) != 0 || address_space.rlim_cur != RLIM_INFINITY ||
      getrlimit(RLIMIT_DATA, &data) != 0 || data.rlim_cur != RLIM_INFINITY)
    GTEST_SKIP() << "an address-space limit is set: the reserve is not taken (the test below)";
  ASSERT_EQ(advised_heap_bytes(), 0) << "advised before the call";
  tune_heap_for_simulation();
  EXPECT_GE(advised_heap_bytes(), 32L << 20);  // most of the 64 MB reserve
  void* block = std::malloc(8 << 20);  // below the mmap threshold: from the advised heap
  ASSERT_NE(block, nullptr);
  std::free(block);
}

// Under an address-space limit the reserve is not taken: the 64 MB of it made runs that fit in
// 30-70 MB die of std::bad_alloc (a reviewer's `ulimit -v 70000`; 80000 ran).
TEST(HeapTuning, RunsUnderAnAddressSpaceLimitWithoutTheReserve) {
#if LCS_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space";
#endif
  const cli_testing::fs::path dir = cli_testing::scratch_dir("heap_tuning_limit");
  const std::string cmd = "ulimit -v 70000; '" + std::string(LCSPICE_BINARY) + "' run '" +
                          cli_testing::circuit("half_wave_rectifier").string() + "' -o '" + (dir / "out.csv").string() +
                          "' >/dev/null 2>'" + (dir / "err.txt").string() + "'";
  const int status = std::system(("sh -c \"" + cmd + "\"").c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cli_testing::read_file(dir / "err.txt");
  EXPECT_GT(cli_testing::read_file(dir / "out.csv").size(), 1000u);
}

}  // namespace
}  // namespace lcs
