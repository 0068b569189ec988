#pragma once
// parallelFor: runs work(i) for i in [0, count) on up to `threads` threads (0 = all cores).
// Work items must be independent; each writes only its own outputs, so results do not
// depend on the thread count.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace btflut {

template <typename Work>
void parallelFor(std::size_t count, int threads, Work&& work) {
    unsigned n = threads > 0 ? static_cast<unsigned>(threads) : std::thread::hardware_concurrency();
    n = std::max(1u, std::min<unsigned>(n, static_cast<unsigned>(std::min<std::size_t>(count, 1u << 16))));
    std::atomic<std::size_t> next{0};
    // The first exception (out of memory) ends every thread's loop and is rethrown here, after
    // every thread has joined: a thread that throws, or one left joinable, would abort.
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto loop = [&] {
        try {
            for (std::size_t i; (i = next.fetch_add(1)) < count;) work(i);
        } catch (...) {
            next = count;
            std::lock_guard lock(failureMutex);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < n; ++t) {
        try {
            pool.emplace_back(loop);
        } catch (...) {  // no thread to be had (a memory limit): the ones there are do the work
            break;
        }
    }
    loop();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace btflut
