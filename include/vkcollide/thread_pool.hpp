// vkcollide: how the narrow phase runs data-parallel loops.
//
// Everything parallel in vkcollide's host code goes through an Executor: one call,
// parallelFor, that runs a loop's chunks on some threads and returns when they are done.
// Two implementations:
//   ThreadPool        vkcollide's own worker threads (the default of CollisionWorld);
//   CallbackExecutor  an engine's job system behind one callback, in the spirit
//                     of PhysX's CpuDispatcher or Jolt's JobSystem: the engine runs task
//                     indices [0, n) on its workers and returns when all have run.
// An engine may also derive from Executor directly.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "vkcollide/export.hpp"

namespace vkcollide {

class VKCOLLIDE_API Executor {
public:
    virtual ~Executor() = default;

    // How many threads may run chunks at the same time (>= 1). Only used to size chunks
    // (a few per thread); results never depend on it.
    virtual unsigned threadCount() const noexcept = 0;

    // Calls body(begin, end) for the consecutive chunks [begin, end) of at most `grain`
    // items (grain 0 counts as 1) that cover [0, count), possibly concurrently and in any
    // order, and returns when all chunks are done; everything a chunk wrote is then
    // visible to the caller. body must only write state owned by its chunk, must not
    // throw and must not call parallelFor on the same executor.
    virtual void parallelFor(std::size_t count, std::size_t grain,
                             const std::function<void(std::size_t, std::size_t)>& body) = 0;

    // A hint that loops able to use `threads` threads (the caller included) follow within
    // about a hundred microseconds: an executor whose threads sleep between calls may start
    // waking them now, so that the first loop that needs them does not wait for them. The
    // narrow phase calls it on entry when its input is large enough, and a world every
    // 50 microseconds while it polls for a detection's GPU work (DetectSettings::
    // limits.wait_poll_us) when the last detection's narrow phase was. Never required for
    // correctness; the default does nothing. Same thread rules as parallelFor.
    virtual void prepare(unsigned threads) noexcept { static_cast<void>(threads); }
};

// An engine's parallel-for: run run_task(k) once for every k in [0, task_count), on any
// threads, in any order, and return when every call has returned. task_count >= 2.
// vkcollide calls it from the thread that calls the world (WorldOptions::executor says
// which calls), one loop at a time: about ten loops per narrow-phase call (none for fewer
// than 2,048 pairs the GPU decided: those run on the calling thread), one per
// updateVertices and per shape measurement; each task is a few microseconds to a millisecond.
using ParallelForCallback =
    std::function<void(std::size_t task_count, const std::function<void(std::size_t task)>& run_task)>;

// An Executor that hands every loop to an engine's job system. Loops of one chunk run on
// the calling thread without calling back.
// Thread safety: as thread safe as the callback; vkcollide never calls it concurrently
// from one narrow-phase call.
class VKCOLLIDE_API CallbackExecutor final : public Executor {
public:
    // `thread_count`: how many of the engine's threads may run tasks at once (0 counts as
    // 1). `parallel_for` must not be empty (an empty one runs every task on the caller).
    CallbackExecutor(unsigned thread_count, ParallelForCallback parallel_for);

    unsigned threadCount() const noexcept override { return thread_count_; }
    void parallelFor(std::size_t count, std::size_t grain,
                     const std::function<void(std::size_t, std::size_t)>& body) override;

private:
    unsigned thread_count_;
    ParallelForCallback parallel_for_;
};

// A fixed-size pool of worker threads, owned by the caller (there is no global pool). The
// thread that calls parallelFor works on the loop too, so a pool of N threads starts
// N - 1 workers. Chunks are handed out with one atomic increment each. After a loop,
// workers poll for about 100 microseconds (the narrow phase runs about ten loops back to
// back), then sleep until the next loop. A loop wakes only as many sleeping workers as it
// has chunks for (as a tree: the caller wakes one, each woken worker up to two more, so
// the last of 15 is awake after about four wake latencies); prepare() starts waking them
// before the loop.
//
// Thread safety: parallelFor may be called from any thread; calls are serialised (one
// loop runs at a time). The destructor must not run concurrently with parallelFor.
class VKCOLLIDE_API ThreadPool final : public Executor {
public:
    // Runs loops on `thread_count` threads, the calling one included; 0 means
    // std::thread::hardware_concurrency() (at least 1). 1 starts no worker. If the system
    // refuses to start threads, the pool keeps the ones it got (down to the calling
    // thread alone); threadCount() tells how many.
    explicit ThreadPool(unsigned thread_count = 0);
    ~ThreadPool() override;

    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Number of threads that run a loop's chunks: the workers plus the calling thread (>= 1).
    unsigned threadCount() const noexcept override { return static_cast<unsigned>(workers_.size()) + 1; }

    // As Executor::parallelFor. A loop of one chunk runs on the calling thread alone.
    void parallelFor(std::size_t count, std::size_t grain,
                     const std::function<void(std::size_t, std::size_t)>& body) override;

    // As Executor::prepare: wakes up to threads - 1 sleeping workers (one now, the others
    // through the tree of wakes) and returns; does nothing while another thread runs a loop.
    void prepare(unsigned threads) noexcept override;

    struct Shared;  // the state workers and the caller share (src/narrow/thread_pool.cpp)

private:
    std::unique_ptr<Shared> shared_;
    std::vector<std::thread> workers_;
    std::mutex submit_mutex_;  // serialises parallelFor calls
};

}  // namespace vkcollide
