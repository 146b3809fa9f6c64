// The C library's heap, set for a simulator's allocation pattern.
#pragma once

namespace lcs {

// Keeps freed blocks up to 32 MB in the heap instead of returning them to the system, so that
// memory freed and allocated again (a sparse factorisation per mode: KLU allocates its L and U
// per factorisation and frees the replaced one) is reused without page faults. glibc's default
// maps every block above a threshold afresh, and the threshold slides with what was freed
// before: the same steps then cost 150 or 250 us each depending on whether formation happened to
// free a large block first (500-stage multiplier, euler, 1000 steps: 10700 page faults against
// 2700, `perf stat -e page-faults`).
//
// The heap is also extended once by 64 MB of address space, advised to use transparent huge
// pages (MADV_HUGEPAGE; the machine's setting is usually "madvise"): its first touches then fault
// 2 MB at a time. On this project's virtual machine a page fault costs tens of microseconds:
// `lcspice run --method euler` of the 500-stage multiplier 2930 -> 519 faults and 0.186 ->
// 0.158 s CPU (least of 12 runs each, interleaved), the 1000-section ladder 0.120 -> 0.095 s,
// 1000 rectifiers 0.140 -> 0.092 s, peak resident memory 1-2 MB more; the small circuits'
// 16-23 ms unchanged. Not taken under an address-space or data limit (RLIMIT_AS, RLIMIT_DATA
// count the reserve: runs that fit in 30-70 MB died of bad_alloc). No effect where the C library
// is not glibc.
void tune_heap_for_simulation();

}  // namespace lcs
