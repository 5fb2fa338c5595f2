#include "vkcollide/thread_pool.hpp"

#include <algorithm>
#include <system_error>

namespace vkcollide {

ThreadPool::ThreadPool(unsigned thread_count) {
    if (thread_count == 0) thread_count = std::max(1u, std::thread::hardware_concurrency());
    workers_.reserve(thread_count);
    for (unsigned i = 0; i < thread_count; ++i) {
        // std::thread reports resource exhaustion by throwing; the API does not throw, so
        // keep the workers that did start (parallelFor copes with any number, even zero).
        try {
            workers_.emplace_back([this] { workerLoop(); });
        } catch (const std::system_error&) {
            break;
        }
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_ready_.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::parallelFor(std::size_t count, std::size_t grain,
                             const std::function<void(std::size_t, std::size_t)>& body) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    if (workers_.empty()) {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
        return;
    }
    std::lock_guard submit_lock(submit_mutex_);
    std::unique_lock lock(mutex_);
    body_ = &body;
    count_ = count;
    grain_ = grain;
    next_ = 0;
    workers_finished_ = 0;
    ++generation_;
    work_ready_.notify_all();
    // Every worker checks in for every generation, so body_ is never used after return.
    work_done_.wait(lock, [this] { return workers_finished_ == workers_.size(); });
    body_ = nullptr;
}

void ThreadPool::workerLoop() {
    std::size_t seen_generation = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
        work_ready_.wait(lock, [&] { return stopping_ || generation_ != seen_generation; });
        if (stopping_) return;
        seen_generation = generation_;
        // Hand out chunks under the lock (chunks are coarse, so contention is small) and
        // run them without it.
        while (next_ < count_) {
            const std::size_t begin = next_;
            const std::size_t end = std::min(count_, begin + grain_);
            next_ = end;
            const auto* body = body_;
            lock.unlock();
            (*body)(begin, end);
            lock.lock();
        }
        if (++workers_finished_ == workers_.size()) work_done_.notify_one();
    }
}

}  // namespace vkcollide
