// The C library's heap, set for a simulator's allocation pattern.
#pragma once

namespace lcs {

// Keeps freed blocks up to 32 MB in the heap instead of returning them to the system, so that
// memory freed and allocated again (a sparse factorisation per mode: KLU allocates its L and U
// per factorisation and frees the replaced one) is reused without page faults. glibc's default
// maps every block above a threshold afresh, and the threshold slides with what was freed
// before: the same steps then cost 150 or 250 us each depending on whether formation happened to
// free a large block first (500-stage multiplier, euler, 1000 steps: 10700 page faults against
// 2700, `perf stat -e page-faults`). No effect where the C library is not glibc.
void tune_heap_for_simulation();

}  // namespace lcs
