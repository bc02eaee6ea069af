// actionstring host library — running independent jobs on threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace actionstring {
namespace host {

/// Runs job(k) for every k in [0, count), at most `workers` at a time, and
/// rethrows the failure of the lowest k, if any, after every job has ended.
/// Jobs must be independent: results then do not depend on the thread count.
template <class Job>
void parallel_for(std::size_t count, std::size_t workers, Job job) {
    workers = std::max<std::size_t>(1, workers);
    std::vector<std::exception_ptr> failures(count);
    for (std::size_t batch = 0; batch < count; batch += workers) {
        std::vector<std::thread> threads;
        for (std::size_t k = batch; k < std::min(count, batch + workers); ++k)
            threads.emplace_back([&failures, &job, k] {
                try {
                    job(k);
                } catch (...) {
                    failures[k] = std::current_exception();
                }
            });
        for (std::thread& t : threads) t.join();
    }
    for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
}

/// Threads worth using on this machine (at least 1).
inline std::size_t hardware_workers() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace host
}  // namespace actionstring
