// The narrow phase's promise that no exception escapes, kept in one place. Executor bodies
// must not throw (an engine's job system, or a worker thread, would terminate), yet host
// memory can run out inside any loop and the sweep stops itself past its box-pair budget
// by throwing. GuardedExecutor wraps the caller's executor: a chunk that throws stores the
// first exception, later chunks of that loop return at once, and the exception is thrown
// again on the calling thread once the loop is over, where the entry points turn it into
// a Result (guardedCall).
#pragma once

#include <atomic>
#include <exception>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>

#include "core/host_memory.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

// Thrown by the sweep past NarrowOptions::max_box_pairs.
struct BoxBudgetExceeded {};

class GuardedExecutor final : public Executor {
public:
    explicit GuardedExecutor(Executor& inner) : inner_(inner) {}

    unsigned threadCount() const noexcept override { return inner_.threadCount(); }
    void prepare(unsigned threads) noexcept override { inner_.prepare(threads); }

    void parallelFor(std::size_t count, std::size_t grain,
                     const std::function<void(std::size_t, std::size_t)>& body) override {
        std::atomic<bool> failed{false};
        std::exception_ptr first;
        std::mutex first_mutex;
        inner_.parallelFor(count, grain, [&](std::size_t begin, std::size_t end) {
            if (failed.load(std::memory_order_relaxed)) return;
            try {
                body(begin, end);
            } catch (...) {
                const std::lock_guard lock(first_mutex);
                if (!first) first = std::current_exception();
                failed.store(true, std::memory_order_relaxed);
            }
        });
        if (first) std::rethrow_exception(first);
    }

private:
    Executor& inner_;
};

// Runs run(guarded executor) and turns what it throws into an error named after `entry`.
template <typename Run>
Result<NarrowResult> guardedCall(const char* entry, Executor& executor, std::size_t max_box_pairs, Run&& run) {
    GuardedExecutor guarded(executor);
    try {
        return hostMemoryGuarded(entry, [&] { return run(guarded); });
    } catch (const BoxBudgetExceeded&) {
        return Error(ErrorCode::LimitExceeded, std::string(entry) + ": more than " + std::to_string(max_box_pairs) +
                                                   " pairs of candidates with overlapping boxes (NarrowOptions::max_box_pairs): "
                                                   "stacked or repeated triangles?");
    }
}

}  // namespace vkcollide::narrow
