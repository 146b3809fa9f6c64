#include "cli/heap_tuning.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace lcs {

void tune_heap_for_simulation() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest: blocks below it come from the heap
  mallopt(M_TRIM_THRESHOLD, 128 << 20);  // and stay there when freed, up to this much at its top
#endif
}

}  // namespace lcs
