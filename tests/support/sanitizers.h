// LCS_UNDER_ASAN: 1 when AddressSanitizer instruments this build. GCC defines
// __SANITIZE_ADDRESS__; clang only answers __has_feature(address_sanitizer). Tests that
// interpose malloc or measure resident memory must know, or they crash or mismeasure under ASan.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define LCS_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LCS_UNDER_ASAN 1
#endif
#endif
#ifndef LCS_UNDER_ASAN
#define LCS_UNDER_ASAN 0
#endif
