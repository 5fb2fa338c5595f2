// vkcollide: a small fixed-size pool of worker threads for data-parallel loops (the narrow phase).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vkcollide {

// Owned by the caller; there is no global pool. The thread that calls parallelFor works on
// the loop too, so a pool of N threads starts N - 1 workers. Workers spin for a few
// microseconds after a loop (the narrow phase runs several in a row), then sleep.
//
// Thread safety: parallelFor may be called from any thread; calls are serialised (one
// loop runs at a time). The destructor must not run concurrently with parallelFor.
class ThreadPool {
public:
    // Runs loops on `thread_count` threads, the calling one included; 0 means
    // std::thread::hardware_concurrency() (at least 1). 1 starts no worker. If the system
    // refuses to start threads, the pool keeps the ones it got (down to the calling
    // thread alone); threadCount() tells how many.
    explicit ThreadPool(unsigned thread_count = 0);
    ~ThreadPool();

    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Number of threads that run a loop's chunks: the workers plus the calling thread (>= 1).
    unsigned threadCount() const noexcept { return static_cast<unsigned>(workers_.size()) + 1; }

    // Calls body(begin, end) for consecutive chunks [begin, end) of at most `grain` items
    // (grain 0 counts as 1) covering [0, count), spread over the workers and the calling
    // thread, and returns when all chunks are done. Chunks run concurrently and in no
    // particular order, so body must only write to state owned by its chunk. body must
    // not throw and must not call parallelFor on the same pool. A loop of one chunk runs
    // on the calling thread alone.
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

private:
    void workerLoop();
    // Runs chunks of the current loop until none is left; called with `lock` held.
    void runChunks(std::unique_lock<std::mutex>& lock);

    std::vector<std::thread> workers_;
    std::mutex submit_mutex_;  // serialises parallelFor calls

    std::mutex mutex_;  // guards everything below but generation_'s reads while spinning
    std::condition_variable work_ready_;
    std::condition_variable work_done_;
    const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
    std::size_t count_ = 0;
    std::size_t grain_ = 1;
    std::size_t next_ = 0;               // first item not yet handed out
    std::size_t chunks_left_ = 0;        // chunks of the current loop not yet finished
    std::atomic<std::size_t> generation_{0};  // bumped once per loop (under mutex_) so workers notice it
    unsigned sleeping_ = 0;              // workers waiting on work_ready_
    bool stopping_ = false;
};

}  // namespace vkcollide
