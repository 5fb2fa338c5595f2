#include "vkcollide/thread_pool.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <system_error>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// How a loop runs (docs/narrow_phase.md has the measurements):
//  - The caller publishes the loop (body, count, grain) and bumps `epoch`; workers that
//    poll see the new epoch, sleeping ones are woken through the futex behind
//    std::atomic::wait. Then everyone, the caller included, takes chunks with one
//    fetch_add on `next` each: no lock, so 16 threads handing out thousands of chunks do
//    not queue on a mutex (a mutex per chunk serialised them).
//  - Waking is a tree: the caller wakes one sleeper and leaves in `wakes` how many more
//    the loop can use (chunks beyond the threads already awake); every worker that returns
//    from its sleep passes up to kWakeFanOut of them on. A futex wake costs the waker
//    microseconds (an IPI per thread), and waking all 15 workers of a 16-thread pool for a
//    loop of two chunks cost the caller more than the loop; now it pays for one. A chain
//    (one wake passed on per worker) woke the 15th worker 15 wake latencies after the
//    call (tens of microseconds each where idle cores sleep deeply or are virtual): later
//    than the narrow phase's exact tests; a tree of two per worker wakes them in four.
//  - prepare() starts such a tree without a loop (an epoch bump with no loop open), so
//    workers asleep since the last call are polling by the time the loops that need them
//    come (the narrow phase calls it on entry).
//  - Finished chunks are counted in `done`, once per thread and loop; the caller waits
//    for done == chunks.
//  - A worker announces itself in `active` before it touches the loop and checks that
//    the loop is still open; the caller closes the loop and waits for active == 0 before
//    it returns, so no worker reads a loop's fields after parallelFor returned, and none
//    can take a chunk of the next loop with the old body.
// The counters the threads write sit on separate cache lines.

namespace vkcollide {
namespace {

// How long an idle worker polls for the next loop before it sleeps. Waking a sleeping
// thread costs tens of microseconds; polling this long costs at most this much CPU per loop.
constexpr auto kPoll = std::chrono::microseconds(100);
// Wakes of the tree each woken worker passes on.
constexpr int kWakeFanOut = 2;

void relax() {
#if defined(__SSE2__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

// Waits until pred() holds: a short busy wait, then yields (the threads we wait for may
// need this core).
template <typename Pred>
void spinUntil(Pred pred) {
    for (unsigned spins = 0; !pred(); ++spins) {
        if (spins < 256) {
            relax();
        } else {
            std::this_thread::yield();
        }
    }
}

}  // namespace

struct ThreadPool::Shared {
    // Written by the caller before a loop opens, read by the threads in it.
    const std::function<void(std::size_t, std::size_t)>* body = nullptr;
    std::size_t count = 0, grain = 1, chunks = 0;

    alignas(64) std::atomic<std::uint32_t> epoch{0};  // bumped once per loop (and to stop)
    std::atomic<bool> open{false};                     // the loop takes new threads
    std::atomic<bool> stopping{false};                 // set before the last epoch bump
    alignas(64) std::atomic<std::size_t> next{0};      // first item not handed out yet
    alignas(64) std::atomic<std::size_t> done{0};      // chunks finished
    alignas(64) std::atomic<int> active{0};            // workers inside the open loop
    alignas(64) std::atomic<int> sleepers{0};          // workers blocked in epoch.wait
    alignas(64) std::atomic<int> wakes{0};             // sleepers still to wake (the tree)

    // Wakes `wanted` sleepers (at most as many as there are): one now, the rest by the
    // tree. The caller has bumped the epoch.
    void wakeSleepers(int wanted) {
        if (wanted <= 0 || sleepers.load() == 0) return;
        wakes.store(wanted - 1);
        epoch.notify_one();
    }

    // Passes up to kWakeFanOut wakes of the tree on, as many as are owed.
    void passWake() {
        for (int k = 0; k < kWakeFanOut; ++k) {
            int owed = wakes.load(std::memory_order_relaxed);
            while (owed > 0 && !wakes.compare_exchange_weak(owed, owed - 1)) {
            }
            if (owed <= 0) return;
            epoch.notify_one();
        }
    }

    // Runs chunks until none is left; returns how many it ran.
    std::size_t runChunks() {
        std::size_t ran = 0;
        for (;;) {
            const std::size_t begin = next.fetch_add(grain, std::memory_order_relaxed);
            if (begin >= count) break;
            (*body)(begin, std::min(count, begin + grain));
            ++ran;
        }
        return ran;
    }

    void workerLoop() {
        std::uint32_t seen = 0;
        for (;;) {
            // Poll, then sleep until the epoch moves.
            const auto poll_until = std::chrono::steady_clock::now() + kPoll;
            for (unsigned spins = 0; epoch.load(std::memory_order_acquire) == seen; ++spins) {
                if ((spins & 63) != 63) {
                    relax();
                    continue;
                }
                if (std::chrono::steady_clock::now() < poll_until) {
                    std::this_thread::yield();
                    continue;
                }
                // The caller bumps the epoch before it reads `sleepers` and we count
                // ourselves before wait() reads the epoch (both sequentially consistent),
                // so either it sees us and notifies, or wait() sees the new epoch.
                sleepers.fetch_add(1);
                epoch.wait(seen);
                sleepers.fetch_sub(1);
                // Whatever woke us (a notify or an epoch that moved before we slept),
                // wakes of the tree may be owed to other sleepers.
                passWake();
            }
            seen = epoch.load(std::memory_order_acquire);
            if (stopping.load(std::memory_order_acquire)) return;
            active.fetch_add(1);
            // A loop closed in the meantime: its caller may be returning. (A loop opened
            // since is complete in memory when `open` reads true, so joining it is fine.)
            if (open.load()) {
                const std::size_t ran = runChunks();
                if (ran) done.fetch_add(ran, std::memory_order_release);
            }
            active.fetch_sub(1, std::memory_order_release);
        }
    }
};

ThreadPool::ThreadPool(unsigned thread_count) : shared_(std::make_unique<Shared>()) {
    if (thread_count == 0) thread_count = std::max(1u, std::thread::hardware_concurrency());
    workers_.reserve(thread_count - 1);
    for (unsigned i = 1; i < thread_count; ++i) {
        // std::thread reports resource exhaustion by throwing; the API does not throw, so
        // keep the workers that did start (parallelFor copes with any number, even zero).
        try {
            workers_.emplace_back([shared = shared_.get()] { shared->workerLoop(); });
        } catch (const std::system_error&) {
            break;
        }
    }
}

ThreadPool::~ThreadPool() {
    shared_->stopping.store(true, std::memory_order_release);
    shared_->epoch.fetch_add(1);
    shared_->epoch.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

void ThreadPool::parallelFor(std::size_t count, std::size_t grain,
                             const std::function<void(std::size_t, std::size_t)>& body) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t chunks = (count - 1) / grain + 1;
    std::lock_guard submit_lock(submit_mutex_);
    if (workers_.empty() || chunks == 1) {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
        return;
    }
    Shared& s = *shared_;
    // No worker is inside a loop here (the previous call waited for active == 0).
    s.body = &body;
    s.count = count;
    s.grain = grain;
    s.chunks = chunks;
    s.next.store(0, std::memory_order_relaxed);
    s.done.store(0, std::memory_order_relaxed);
    s.open.store(true);
    s.epoch.fetch_add(1);
    // Threads the loop can use besides the caller, less those awake (polling) already.
    const int useful = static_cast<int>(std::min<std::size_t>(chunks - 1, workers_.size()));
    const int sleeping = s.sleepers.load();
    s.wakeSleepers(useful - (static_cast<int>(workers_.size()) - sleeping));

    const std::size_t ran = s.runChunks();
    if (ran) s.done.fetch_add(ran, std::memory_order_relaxed);
    spinUntil([&] { return s.done.load(std::memory_order_acquire) == chunks; });
    s.open.store(false);
    spinUntil([&] { return s.active.load() == 0; });
}

void ThreadPool::prepare(unsigned threads) noexcept {
    if (workers_.empty() || threads < 2) return;
    // A loop running on another thread keeps the workers awake anyway; never block on it.
    if (!submit_mutex_.try_lock()) return;
    std::lock_guard submit_lock(submit_mutex_, std::adopt_lock);
    Shared& s = *shared_;
    // An epoch with no loop open: woken workers find `open` false and go back to polling.
    s.epoch.fetch_add(1);
    const int wanted = static_cast<int>(std::min<std::size_t>(threads - 1, workers_.size()));
    const int sleeping = s.sleepers.load();
    s.wakeSleepers(wanted - (static_cast<int>(workers_.size()) - sleeping));
}

CallbackExecutor::CallbackExecutor(unsigned thread_count, ParallelForCallback parallel_for)
    : thread_count_(std::max(1u, thread_count)), parallel_for_(std::move(parallel_for)) {}

void CallbackExecutor::parallelFor(std::size_t count, std::size_t grain,
                                   const std::function<void(std::size_t, std::size_t)>& body) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t chunks = (count - 1) / grain + 1;
    const auto run_task = [&](std::size_t task) {
        const std::size_t begin = task * grain;
        body(begin, std::min(count, begin + grain));
    };
    if (chunks == 1 || !parallel_for_) {
        for (std::size_t task = 0; task < chunks; ++task) run_task(task);
        return;
    }
    parallel_for_(chunks, run_task);
}

}  // namespace vkcollide
