// One libFuzzer target per parser: compiled once per name in fuzz_targets.h, with
// BTFLUT_FUZZ_TARGET set to it (tests/fuzz/CMakeLists.txt).
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const auto run = [] {
        for (const btflut::fuzz::Target& t : btflut::fuzz::kTargets)
            if (t.name == BTFLUT_FUZZ_TARGET) return t.accepts;
        BTFLUT_CHECK(!"unknown BTFLUT_FUZZ_TARGET");
        return btflut::fuzz::kTargets[0].accepts;
    }();
    (void)run(data, size);
    return 0;
}
