// Small building blocks for the narrow phase's parallel loops: task sizes, uninitialised
// scratch buffers, an exclusive scan and a stream compaction over an Executor.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/huge_pages.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

inline std::size_t taskCount(std::size_t count, std::size_t grain) { return count == 0 ? 0 : (count - 1) / grain + 1; }

// Items per task: about `tasks_per_thread` tasks per thread, within [min_grain, max_grain].
// More tasks than threads balance uneven work; fewer, larger ones cost fewer hand-outs.
inline std::size_t grainFor(std::size_t count, unsigned threads, std::size_t tasks_per_thread, std::size_t min_grain,
                            std::size_t max_grain) {
    return std::clamp<std::size_t>(count / (std::size_t{std::max(1u, threads)} * tasks_per_thread), min_grain, max_grain);
}

// Runs body over [0, count) in chunks, on the executor when there is one.
inline void forChunks(Executor* executor, std::size_t count, std::size_t grain,
                      const std::function<void(std::size_t, std::size_t)>& body) {
    if (executor) {
        executor->parallelFor(count, grain, body);
    } else {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
    }
}

// A growable array of a trivially copyable type that is never zeroed: resize() keeps the
// capacity of earlier calls and leaves new elements indeterminate (every element is
// written before it is read). Large arrays reused from call to call cost no page faults.
template <typename T>
class Buffer {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

public:
    // Size n; contents are lost when the capacity grows.
    void resize(std::size_t n) {
        if (n > capacity_) {
            data_.reset();
            const std::size_t capacity = std::max(n, capacity_ + capacity_ / 2);
            data_.reset(new T[capacity]);
            capacity_ = capacity;
        }
        size_ = n;
    }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    T* data() noexcept { return data_.get(); }
    const T* data() const noexcept { return data_.get(); }
    T& operator[](std::size_t i) noexcept { return data_[i]; }
    const T& operator[](std::size_t i) const noexcept { return data_[i]; }
    T* begin() noexcept { return data_.get(); }
    T* end() noexcept { return data_.get() + size_; }
    const T* begin() const noexcept { return data_.get(); }
    const T* end() const noexcept { return data_.get() + size_; }
    void swap(Buffer& other) noexcept {
        std::swap(data_, other.data_);
        std::swap(size_, other.size_);
        std::swap(capacity_, other.capacity_);
    }

private:
    std::unique_ptr<T[]> data_;
    std::size_t size_ = 0, capacity_ = 0;
};

// Sizing arrays to n elements that the caller then overwrites: v.resize(n) within the
// capacity; beyond it, from `touch_from` bytes, a new array of value-initialised elements
// (the old contents are lost), in huge pages where the kernel gives them
// (core/huge_pages.hpp), which the executor's threads touch before resize()'s one-thread
// pass: a fresh vector's page faults, taken by one thread, cost 13.6 ms for the 27 MB of 1.7M
// pairs on the H200's host (docs/api.md), more than the rest of the host's work for them.
// (That pass writes nothing for a type whose default constructor leaves it unset, as
// TrianglePair's does.) Below `touch_from` the new array's pages fault where it is first
// written; a detection's result memory, made ready while the GPU works, is touched from a
// few pages on (CollisionWorld::Impl::prepareResultMemory).
namespace fresh {

inline constexpr std::size_t kTouchBytes = std::size_t{1} << 20;  // a task's share of the pages
inline constexpr std::size_t kTouchFrom = 2 * kTouchBytes;       // resizeFresh's default
// A touch writes one byte per page: that faults the page in, and the kernel hands it out
// zeroed. Writing every byte, as before, added a memset over the whole array: on the H100's
// host detect()'s result memory took 0.01-0.5 ms less to make ready with one write a page
// (run 50: stack-touching's 9 MB 1.94 -> 1.44 ms, 0.89 -> 0.44 where the memory came back
// from a dropped result). The smallest page size: larger pages are written more than once.
inline constexpr std::size_t kPageBytes = 4096;

// One array on its way to n elements: `fresh` holds the new storage (no elements yet) where
// the old capacity is too small.
template <typename T>
struct Plan {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
    std::vector<T>& v;
    std::size_t n;
    std::vector<T> fresh{};

    Plan(std::vector<T>& into, std::size_t count, std::size_t touch_from = kTouchFrom) : v(into), n(count) {
        if (n <= v.capacity() || n * sizeof(T) < touch_from) return;
        fresh.reserve(n);
        adviseHugePages(fresh.data(), bytes());
    }
    bool isNew() const { return fresh.capacity() > 0; }
    // Allocated storage, no elements yet: raw bytes, written before resize() makes the elements.
    unsigned char* data() { return reinterpret_cast<unsigned char*>(fresh.data()); }
    std::size_t bytes() const { return isNew() ? n * sizeof(T) : 0; }
    std::size_t pageTasks() const { return taskCount(bytes(), kTouchBytes); }
    void touch(std::size_t task) {
        // volatile: the bytes are never read before they are overwritten, so plain stores
        // could be dropped.
        volatile unsigned char* const first = data() + task * kTouchBytes;
        const std::size_t length = std::min(kTouchBytes, bytes() - task * kTouchBytes);
        for (std::size_t at = 0; at < length; at += kPageBytes) first[at] = 0;
        first[length - 1] = 0;  // the last page, where the array is not page-aligned (length >= 1: task < pageTasks())
    }
    void finish() {
        if (!isNew()) {
            v.resize(n);
            return;
        }
        fresh.resize(n);
        v.swap(fresh);
    }
};

}  // namespace fresh

template <typename T>
void resizeFresh(std::vector<T>& v, std::size_t n, Executor& ex) {
    fresh::Plan<T> plan(v, n);
    ex.parallelFor(plan.pageTasks(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) plan.touch(k);
    });
    plan.finish();
}

// The same for two arrays at once, a result's pairs (`touched`) and responses (`zeroed`).
// Where both are new: one parallel loop whose first task is the responses' resize(), which
// faults their pages as it value-initialises them (one thread; they are not touched apart),
// while the other tasks touch the pairs' pages; then the pairs' resize(), which writes
// nothing (TrianglePair's constructor leaves its ids unset). The responses' zeroing used to
// follow the loop: on the H100's host it is about 0.4 ms for stack-mating's 5 MB (11-14 GB/s
// on one thread, run 51), which the GPU's span does not always cover (run 52: the prepare
// stage 2.7 ms against a 2.45 ms span). Otherwise every new page is touched in one loop,
// then the resize()s run.
template <typename A, typename B>
void resizeFresh(std::vector<A>& touched, std::size_t na, std::vector<B>& zeroed, std::size_t nb, Executor& ex,
                 std::size_t touch_from = fresh::kTouchFrom) {
    fresh::Plan<A> pa(touched, na, touch_from);
    fresh::Plan<B> pb(zeroed, nb, touch_from);
    if (pa.isNew() && pb.isNew()) {
        ex.parallelFor(pa.pageTasks() + 1, 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) k == 0 ? pb.finish() : pa.touch(k - 1);
        });
        pa.finish();
        return;
    }
    const std::size_t tasks_a = pa.pageTasks();
    ex.parallelFor(tasks_a + pb.pageTasks(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) k < tasks_a ? pa.touch(k) : pb.touch(k - tasks_a);
    });
    pa.finish();  // at most one of them is new: at most one long pass
    pb.finish();
}

// Below this many items the scan, the compaction and the sorts run on the calling thread.
// Low on purpose: the GPU host's cores take about 85 ns per pair for the pair path's
// serial sorting (7K pairs: 0.6 ms on one thread, 0.3 ms on 16 with these thresholds).
inline constexpr std::size_t kSerialBelow = 1u << 12;

// Replaces data[i] by the sum of data[0..i) and returns the total.
template <typename T>
T exclusiveScan(Executor& executor, T* data, std::size_t n) {
    const auto serial = [](T* first, T* last, T offset) {
        for (T* p = first; p != last; ++p) {
            const T here = *p;
            *p = offset;
            offset += here;
        }
        return offset;
    };
    if (n < kSerialBelow || executor.threadCount() == 1) return serial(data, data + n, T{0});
    const std::size_t grain = grainFor(n, executor.threadCount(), 2, 1024, std::size_t(1) << 30);
    std::vector<T> sums(taskCount(n, grain) + 1, T{0});
    executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        T s{0};
        for (std::size_t i = begin; i < end; ++i) s += data[i];
        sums[begin / grain] = s;
    });
    const T total = serial(sums.data(), sums.data() + sums.size() - 1, T{0});
    executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        serial(data + begin, data + end, sums[begin / grain]);
    });
    return total;
}

// Writes the items of [0, n) that keep(i) accepts, in order, through emit(out_position,
// i), and returns how many there are. keep must be a pure function of i.
template <typename Keep, typename Emit>
std::size_t compact(Executor& executor, std::size_t n, Keep&& keep, Emit&& emit) {
    if (n < kSerialBelow || executor.threadCount() == 1) {
        std::size_t out = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (keep(i)) emit(out++, i);
        }
        return out;
    }
    const std::size_t grain = grainFor(n, executor.threadCount(), 2, 1024, std::size_t(1) << 30);
    std::vector<std::size_t> counts(taskCount(n, grain) + 1, 0);
    executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t c = 0;
        for (std::size_t i = begin; i < end; ++i) c += keep(i) ? 1 : 0;
        counts[begin / grain] = c;
    });
    std::size_t total = 0;
    for (std::size_t& c : counts) {
        const std::size_t here = c;
        c = total;
        total += here;
    }
    executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t out = counts[begin / grain];
        for (std::size_t i = begin; i < end; ++i) {
            if (keep(i)) emit(out++, i);
        }
    });
    return total;
}

}  // namespace vkcollide::narrow
