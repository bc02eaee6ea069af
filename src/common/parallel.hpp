// actionstring host library — running independent jobs on threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace actionstring {
namespace host {

/// True on a thread parallel_for() started: a nested parallel_for() then runs
/// its jobs inline rather than oversubscribing the cores.
inline bool& inside_parallel_for() {
    thread_local bool inside = false;
    return inside;
}

/// Runs job(k) for every k in [0, count), at most `workers` at a time, and
/// rethrows the failure of the lowest k, if any, after every job has ended.
/// Jobs must be independent: results then do not depend on the thread count.
/// Each of min(workers, count) threads takes every workers-th k, so a loop
/// of many short jobs starts its threads once; one worker, or a call from
/// inside another parallel_for(), runs them inline.
template <class Job>
void parallel_for(std::size_t count, std::size_t workers, Job job) {
    workers = std::max<std::size_t>(1, std::min(workers, count));
    std::vector<std::exception_ptr> failures(count);
    auto run = [&failures, &job, count, workers](std::size_t first) {
        for (std::size_t k = first; k < count; k += workers) {
            try {
                job(k);
            } catch (...) {
                failures[k] = std::current_exception();
            }
        }
    };
    if (workers == 1 || inside_parallel_for()) {
        for (std::size_t t = 0; t < workers; ++t) run(t);
    } else {
        std::vector<std::thread> threads;
        for (std::size_t t = 0; t < workers; ++t)
            threads.emplace_back([&run, t] {
                inside_parallel_for() = true;
                run(t);
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
