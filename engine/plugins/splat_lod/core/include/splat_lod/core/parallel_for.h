#pragma once
// Internal to the reference renderer: runs body(0..count−1) on a few std::threads. Tasks are
// handed out dynamically, so each body must write only its own outputs; the result then does not
// depend on the thread count or the scheduling. The first exception is rethrown on the caller.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace splat_lod::reference::detail {

inline int resolve_thread_count(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

template <typename Body>
void parallel_for(std::size_t count, int threads, const Body& body) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    const auto worker = [&] {
        try {
            for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) body(i);
        } catch (...) {
            const std::lock_guard lock(error_mutex);
            if (!error) error = std::current_exception();
            next.store(count);
        }
    };
    const std::size_t helpers =
        std::min<std::size_t>(count, static_cast<std::size_t>(std::max(threads, 1))) - (count > 0);
    std::vector<std::thread> pool;
    pool.reserve(helpers);
    for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(worker);
    worker();
    for (auto& thread : pool) thread.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace splat_lod::reference::detail
