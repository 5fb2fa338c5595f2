#include "vkcollide/thread_pool.hpp"

#include <algorithm>
#include <chrono>
#include <system_error>

namespace vkcollide {
namespace {

// How long an idle worker polls for the next loop before it sleeps. The narrow phase runs
// about six loops back to back; waking a sleeping thread costs tens of microseconds each
// time, polling this long costs at most this much CPU per loop.
constexpr auto kSpin = std::chrono::microseconds(100);

}  // namespace

ThreadPool::ThreadPool(unsigned thread_count) {
    if (thread_count == 0) thread_count = std::max(1u, std::thread::hardware_concurrency());
    workers_.reserve(thread_count - 1);
    for (unsigned i = 1; i < thread_count; ++i) {
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
        generation_.fetch_add(1, std::memory_order_release);  // ends the workers' polling
    }
    work_ready_.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::parallelFor(std::size_t count, std::size_t grain,
                             const std::function<void(std::size_t, std::size_t)>& body) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    std::lock_guard submit_lock(submit_mutex_);
    const std::size_t chunks = (count - 1) / grain + 1;
    if (workers_.empty() || chunks == 1) {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
        return;
    }
    std::unique_lock lock(mutex_);
    body_ = &body;
    count_ = count;
    grain_ = grain;
    next_ = 0;
    chunks_left_ = chunks;
    generation_.fetch_add(1, std::memory_order_release);
    // Wake only as many sleepers as there are chunks for (the caller takes one); polling
    // workers see the new generation by themselves.
    const std::size_t wanted = std::min<std::size_t>(chunks - 1, sleeping_);
    if (wanted == sleeping_) {
        work_ready_.notify_all();
    } else {
        for (std::size_t i = 0; i < wanted; ++i) work_ready_.notify_one();
    }
    runChunks(lock);
    // A worker touches body_ only for a chunk it took, and every chunk taken is waited
    // for here, so body_ is never used after return even by workers that wake late.
    work_done_.wait(lock, [this] { return chunks_left_ == 0; });
    body_ = nullptr;
}

void ThreadPool::runChunks(std::unique_lock<std::mutex>& lock) {
    // Hand out chunks under the lock (chunks are coarse, so contention is small) and run
    // them without it.
    while (next_ < count_) {
        const std::size_t begin = next_;
        const std::size_t end = std::min(count_, begin + grain_);
        next_ = end;
        const auto* body = body_;
        lock.unlock();
        (*body)(begin, end);
        lock.lock();
        if (--chunks_left_ == 0) work_done_.notify_one();
    }
}

void ThreadPool::workerLoop() {
    std::size_t seen_generation = 0;
    for (;;) {
        // Poll briefly: the next loop usually follows within microseconds.
        const auto poll_until = std::chrono::steady_clock::now() + kSpin;
        while (generation_.load(std::memory_order_acquire) == seen_generation &&
               std::chrono::steady_clock::now() < poll_until) {
            std::this_thread::yield();
        }
        std::unique_lock lock(mutex_);
        ++sleeping_;
        work_ready_.wait(lock, [&] { return stopping_ || generation_.load(std::memory_order_relaxed) != seen_generation; });
        --sleeping_;
        if (stopping_) return;
        seen_generation = generation_.load(std::memory_order_relaxed);
        runChunks(lock);
    }
}

}  // namespace vkcollide
