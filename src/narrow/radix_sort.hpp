// LSD radix sorts on 64-bit keys: the narrow phase's (object, triangle) keys, its
// (rank, rank) pair keys and the pair path's (id, id) keys. Byte digits; a digit that is
// the same in every key is skipped, so keys that use few bits take few passes.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "narrow/parallel.hpp"

namespace vkcollide::narrow {

// A key and the index of the item it belongs to.
struct KeyIndex {
    std::uint64_t key;
    std::uint32_t index;
};

inline std::uint64_t radixKey(std::uint64_t key) { return key; }
inline std::uint64_t radixKey(const KeyIndex& item) { return item.key; }

// Sorts by radixKey, stable (equal keys keep their order). The `ignored_low_bytes` low
// bytes of the key are not sorted by (they may carry a payload: a stable sort of input
// ordered by the payload keeps that order among equal keys). Below a few hundred items a
// comparison sort is faster than the histogram passes.
template <typename T>
void radixSort(std::vector<T>& io, int ignored_low_bytes = 0) {
    const std::size_t n = io.size();
    if (n < 2048) {
        const int shift = 8 * ignored_low_bytes;
        std::stable_sort(io.begin(), io.end(), [shift](const T& a, const T& b) {
            return (radixKey(a) >> shift) < (radixKey(b) >> shift);
        });
        return;
    }
    std::array<std::array<std::size_t, 256>, 8> counts{};
    for (const T& item : io) {
        const std::uint64_t key = radixKey(item);
        for (int d = ignored_low_bytes; d < 8; ++d) ++counts[d][(key >> (8 * d)) & 0xff];
    }
    std::vector<T> scratch(n);
    for (int d = ignored_low_bytes; d < 8; ++d) {
        std::array<std::size_t, 256>& count = counts[d];
        if (std::find(count.begin(), count.end(), n) != count.end()) continue;  // one value: nothing to do
        std::size_t total = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = total;
            total += here;
        }
        for (const T& item : io) scratch[count[(radixKey(item) >> (8 * d)) & 0xff]++] = item;
        io.swap(scratch);
    }
}

// The parallel form, for the large arrays of a million-candidate call: sorts data[0, n)
// by the low `key_bits` bits of radixKey (the others must be zero), stable, using
// scratch (resized to n). Each byte digit costs a counting pass and a scatter pass, both
// in parallel over fixed chunks (per-chunk counts, prefix sums digit-major, chunk-minor),
// so the result is the stable order whatever the thread count. Digits that are the same
// in every key are detected in a first counting pass and skipped.
template <typename T>
void parallelRadixSort(Executor& executor, Buffer<T>& data, Buffer<T>& scratch, int key_bits = 64) {
    const std::size_t n = data.size();
    const int digits = std::clamp((key_bits + 7) / 8, 0, 8);
    if (n < 2 || digits == 0) return;
    const unsigned threads = executor.threadCount();
    if (n < kSerialBelow || threads == 1) {
        std::vector<T> v(data.begin(), data.end());
        radixSort(v, 0);
        std::copy(v.begin(), v.end(), data.begin());
        return;
    }
    const std::size_t grain = grainFor(n, threads, 2, 8192, std::size_t(1) << 30);
    const std::size_t chunks = taskCount(n, grain);
    // Which digits vary: one pass over all digits (OR of key XOR first key).
    std::vector<std::uint64_t> varying(chunks, 0);
    {
        const std::uint64_t first = radixKey(data[0]);
        executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
            std::uint64_t v = 0;
            for (std::size_t i = begin; i < end; ++i) v |= radixKey(data[i]) ^ first;
            varying[begin / grain] = v;
        });
    }
    std::uint64_t any = 0;
    for (std::uint64_t v : varying) any |= v;
    scratch.resize(n);
    std::vector<std::array<std::size_t, 256>> counts(chunks);
    for (int d = 0; d < digits; ++d) {
        const int shift = 8 * d;
        if (((any >> shift) & 0xff) == 0) continue;
        executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
            std::array<std::size_t, 256>& c = counts[begin / grain];
            c.fill(0);
            for (std::size_t i = begin; i < end; ++i) ++c[(radixKey(data[i]) >> shift) & 0xff];
        });
        std::size_t total = 0;
        for (std::size_t digit = 0; digit < 256; ++digit) {
            for (std::size_t c = 0; c < chunks; ++c) {
                const std::size_t here = counts[c][digit];
                counts[c][digit] = total;
                total += here;
            }
        }
        executor.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
            std::array<std::size_t, 256>& next = counts[begin / grain];
            for (std::size_t i = begin; i < end; ++i) scratch[next[(radixKey(data[i]) >> shift) & 0xff]++] = data[i];
        });
        data.swap(scratch);
    }
}

}  // namespace vkcollide::narrow

namespace vkcollide::narrow {

// Sorts plain 64-bit keys that use the low `key_bits` bits, in parallel, for the pair
// path's (slot, slot) keys: one pass by the top 11 bits into 2048 buckets (per-task
// counts, stable), then every bucket on its own, in parallel, by LSD byte digits in
// memory that stays in cache. Two passes over the whole array instead of one per byte.
void parallelSortKeys(Executor& executor, Buffer<std::uint64_t>& io_keys, Buffer<std::uint64_t>& scratch, int key_bits);

}  // namespace vkcollide::narrow
