#pragma once
// Programmer-error checks (pbrt style): a failed CHECK is a bug in btflut, never bad input.
// Bad input is reported through Result<T> (result.h) instead.

#include <cstdio>
#include <cstdlib>

#define BTFLUT_CHECK(cond)                                                                                \
    do {                                                                                                  \
        if (!(cond)) {                                                                                    \
            std::fprintf(stderr, "%s:%d: internal error: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); \
            std::abort();                                                                                 \
        }                                                                                                 \
    } while (0)

#ifdef NDEBUG
#define BTFLUT_DCHECK(cond) ((void)0)
#else
#define BTFLUT_DCHECK(cond) BTFLUT_CHECK(cond)
#endif

namespace btflut {
/// True in the libFuzzer build (tools/fuzz.sh): readers then accept any checksum (btflut's
/// chunk CRCs, PNG's CRCs and Adler-32), so that the fuzzer reaches the checks behind them.
#ifdef BTFLUT_FUZZING
inline constexpr bool kFuzzingBuild = true;
#else
inline constexpr bool kFuzzingBuild = false;
#endif
}  // namespace btflut
