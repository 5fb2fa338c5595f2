// vkcollide: a small fixed-size pool of worker threads for data-parallel loops (the narrow phase).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vkcollide {

// Owned by the caller; there is no global pool. Workers sleep between loops.
//
// Thread safety: parallelFor may be called from any thread; calls are serialised (one
// loop runs at a time). The destructor must not run concurrently with parallelFor.
class ThreadPool {
public:
    // Starts `thread_count` workers; 0 means std::thread::hardware_concurrency() (at least
    // 1). If the system refuses to start threads, the pool keeps the ones it got and,
    // with none, runs loops on the calling thread; threadCount() tells which.
    explicit ThreadPool(unsigned thread_count = 0);
    ~ThreadPool();

    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Number of worker threads (0: loops run on the calling thread).
    unsigned threadCount() const noexcept { return static_cast<unsigned>(workers_.size()); }

    // Calls body(begin, end) for consecutive chunks [begin, end) of at most `grain` items
    // (grain 0 counts as 1) covering [0, count), spread over the workers, and returns
    // when all chunks are done. Chunks run concurrently and in no particular order, so
    // body must only write to state owned by its chunk. body must not throw and must not
    // call parallelFor on the same pool.
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

private:
    void workerLoop();

    std::vector<std::thread> workers_;
    std::mutex submit_mutex_;  // serialises parallelFor calls

    std::mutex mutex_;  // guards everything below
    std::condition_variable work_ready_;
    std::condition_variable work_done_;
    const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
    std::size_t count_ = 0;
    std::size_t grain_ = 1;
    std::size_t next_ = 0;           // first item not yet handed out
    std::size_t generation_ = 0;     // bumped once per loop so sleeping workers notice it
    unsigned workers_finished_ = 0;  // workers done with the current generation
    bool stopping_ = false;
};

}  // namespace vkcollide
