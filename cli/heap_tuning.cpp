#include "cli/heap_tuning.h"

#include <cstdint>
#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <sys/mman.h>
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
  // Extend the heap once by kHeapReserve (address space only) and ask for huge pages on it.
  mallopt(M_TOP_PAD, static_cast<int>(kHeapReserve));
  void* probe = std::malloc(kHugePage);
  if (probe == nullptr) return;
  const auto start = reinterpret_cast<std::uintptr_t>(probe);
  std::free(probe);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default again: later growth is the same as before
  const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const auto from = (start + kHugePage - 1) & ~(kHugePage - 1);
  if (top > from) madvise(reinterpret_cast<void*>(from), top - from, MADV_HUGEPAGE);
#endif
}

}  // namespace lcs
