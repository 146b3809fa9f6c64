#include "cli/heap_tuning.h"

#include <cstdint>
#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace lcs {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;   // x86-64 and arm64's transparent huge page
constexpr std::size_t kHeapReserve = std::size_t{64} << 20;
}  // namespace

void tune_heap_for_simulation() {
#if defined(__GLIBC__) && defined(__linux__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest: blocks below it come from the heap
  mallopt(M_TRIM_THRESHOLD, 128 << 20);  // and stay there when freed, up to this much at its top
  // Extend the heap once by kHeapReserve and ask for huge pages on it. The reserve is address
  // space, which RLIMIT_AS and RLIMIT_DATA count: under either limit it is not taken (64 MB of
  // it made runs that fit in 30-70 MB die of bad_alloc).
  rlimit address_space{}, data{};
  if (getrlimit(RLIMIT_AS, &address_space) != 0 || address_space.rlim_cur != RLIM_INFINITY) return;
  if (getrlimit(RLIMIT_DATA, &data) != 0 || data.rlim_cur != RLIM_INFINITY) return;
  mallopt(M_TOP_PAD, static_cast<int>(kHeapReserve));
  void* probe = std::malloc(kHugePage);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default again: later growth is the same as before
  if (probe == nullptr) return;
  const auto start = reinterpret_cast<std::uintptr_t>(probe);
  std::free(probe);
  const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const auto from = (start + kHugePage - 1) & ~(kHugePage - 1);
  if (top > from) madvise(reinterpret_cast<void*>(from), top - from, MADV_HUGEPAGE);
#endif
}

}  // namespace lcs
