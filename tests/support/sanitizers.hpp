#pragma once
// Whether this test executable, and so the chaosweep binary of the same build
// that it runs, is built under a sanitizer. GCC says so by
// __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__; clang (14, the debug preset's
// compiler) defines neither and answers __has_feature instead.
#if defined(__SANITIZE_ADDRESS__)
#define CHAOSWEEP_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CHAOSWEEP_TEST_ASAN 1
#endif
#endif

#if defined(__SANITIZE_THREAD__)
#define CHAOSWEEP_TEST_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define CHAOSWEEP_TEST_TSAN 1
#endif
#endif

#if defined(CHAOSWEEP_TEST_ASAN) || defined(CHAOSWEEP_TEST_TSAN)
#define CHAOSWEEP_TEST_SANITIZED 1
#endif
