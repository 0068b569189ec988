#pragma once
// parallelFor: runs work(i) for i in [0, count) on up to `threads` threads (0 = all cores).
// Work items must be independent; each writes only its own outputs, so results do not
// depend on the thread count. LockstepThreads: the same threads running one short task
// together again and again (a training step's share of a batch).

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace btflut {

/// The threads a count of 0 (all cores) or more means: at least 1.
inline int threadCount(int threads) {
    return std::max(1, threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency()));
}

template <typename Work>
void parallelFor(std::size_t count, int threads, Work&& work) {
    auto n = static_cast<unsigned>(threadCount(threads));
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

namespace btflut {

/// Threads that run one task together, again and again, with the caller as thread 0: the
/// data-parallel step of a training loop, where a step is too short (milliseconds) to start
/// threads for. run(task) calls task(t) on every thread t in [0, size()) and returns when all
/// are done; the first exception a thread throws is rethrown there. Threads that cannot be
/// had (a memory limit) leave fewer of them.
class LockstepThreads {
public:
    explicit LockstepThreads(int threads) {
        const auto n = static_cast<unsigned>(threadCount(threads));
        for (unsigned t = 1; t < n; ++t) {
            try {
                m_pool.emplace_back([this, t] { loop(t); });
            } catch (...) {
                break;
            }
        }
    }
    ~LockstepThreads() {
        {
            std::lock_guard lock(m_mutex);
            m_stop = true;
            ++m_generation;
        }
        m_start.notify_all();
        for (auto& t : m_pool) t.join();
    }
    LockstepThreads(const LockstepThreads&) = delete;
    LockstepThreads& operator=(const LockstepThreads&) = delete;

    int size() const { return static_cast<int>(m_pool.size()) + 1; }

    template <typename Task>
    void run(Task&& task) {
        m_task = [&task](int t) { task(t); };
        {
            std::lock_guard lock(m_mutex);
            m_running = m_pool.size();
            ++m_generation;
        }
        m_start.notify_all();
        call(0);
        std::unique_lock lock(m_mutex);
        m_done.wait(lock, [this] { return m_running == 0; });
        if (m_failure) std::rethrow_exception(std::exchange(m_failure, nullptr));
    }

private:
    void call(unsigned t) {
        try {
            m_task(static_cast<int>(t));
        } catch (...) {
            std::lock_guard lock(m_mutex);
            if (!m_failure) m_failure = std::current_exception();
        }
    }
    void loop(unsigned t) {
        std::uint64_t seen = 0;
        for (;;) {
            {
                std::unique_lock lock(m_mutex);
                m_start.wait(lock, [&] { return m_generation != seen; });
                seen = m_generation;
                if (m_stop) return;
            }
            call(t);
            std::lock_guard lock(m_mutex);
            if (--m_running == 0) m_done.notify_one();
        }
    }

    std::vector<std::thread> m_pool;
    std::function<void(int)> m_task;
    std::mutex m_mutex;
    std::condition_variable m_start, m_done;
    std::uint64_t m_generation = 0;
    std::size_t m_running = 0;
    bool m_stop = false;
    std::exception_ptr m_failure;
};

}  // namespace btflut
