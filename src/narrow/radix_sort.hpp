// LSD radix sorts on 64-bit keys: the narrow phase's (object, triangle) keys, its
// (rank, rank) pair keys and the pair path's (id, id) keys. Byte digits; a digit that is
// the same in every key is skipped, so keys that use few bits take few passes.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "narrow/parallel.hpp"

namespace vkcollide::narrow {

// Bits a sort key needs to hold values up to `max_value` (at least 1).
inline int keyBits(std::uint64_t max_value) { return std::max(1, static_cast<int>(std::bit_width(max_value))); }

// A key and the index of the item it belongs to.
struct KeyIndex {
    std::uint64_t key;
    std::uint32_t index;
};

inline std::uint64_t radixKey(std::uint64_t key) { return key; }
inline std::uint64_t radixKey(const KeyIndex& item) { return item.key; }

// Serial LSD by byte digits of bits [first_bit, key_bits) of radixKey, stable, through tmp
// (same length); the result ends in [first, last). Digits equal in every key are skipped.
template <typename T>
void lsdSortBits(T* first, T* last, T* tmp, int first_bit, int key_bits) {
    const std::size_t n = static_cast<std::size_t>(last - first);
    if (n < 2 || key_bits <= first_bit) return;
    if (n <= 32) {  // insertion sort: the many tiny buckets of parallelSortKeys
        for (std::size_t i = 1; i < n; ++i) {
            const T item = first[i];
            const std::uint64_t key = radixKey(item) >> first_bit;
            std::size_t j = i;
            for (; j > 0 && (radixKey(first[j - 1]) >> first_bit) > key; --j) first[j] = first[j - 1];
            first[j] = item;
        }
        return;
    }
    std::uint64_t varying = 0;
    const std::uint64_t first_key = radixKey(first[0]);
    for (std::size_t i = 1; i < n; ++i) varying |= radixKey(first[i]) ^ first_key;
    T* from = first;
    T* to = tmp;
    for (int shift = first_bit; shift < key_bits; shift += 8) {
        if (((varying >> shift) & 0xff) == 0) continue;
        std::size_t count[256] = {};
        for (std::size_t i = 0; i < n; ++i) ++count[(radixKey(from[i]) >> shift) & 0xff];
        std::size_t total = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = total;
            total += here;
        }
        for (std::size_t i = 0; i < n; ++i) to[count[(radixKey(from[i]) >> shift) & 0xff]++] = from[i];
        std::swap(from, to);
    }
    if (from != first) std::copy(from, from + n, first);
}

// The parallel form, for the large arrays of a million-candidate call: sorts data[0, n)
// by bits [first_bit, key_bits) of radixKey (the bits above must be zero), stable, using
// scratch (resized to n). Bits below first_bit are not sorted by: pass first_bit > 0 only
// when the input is already in ascending order of them (a payload such as the item's own
// index), so a stable sort of the rest finishes the job with fewer passes. Each byte
// digit costs a counting pass and a scatter pass, both in parallel over fixed chunks
// (per-chunk counts, prefix sums digit-major, chunk-minor), so the result is the stable
// order whatever the thread count. Digits that are the same in every key are detected in
// a first counting pass and skipped.
template <typename T>
void parallelRadixSort(Executor& executor, Buffer<T>& data, Buffer<T>& scratch, int key_bits = 64, int first_bit = 0) {
    const std::size_t n = data.size();
    key_bits = std::clamp(key_bits, 0, 64);
    if (n < 2 || key_bits <= first_bit) return;
    const unsigned threads = executor.threadCount();
    scratch.resize(n);
    if (n < kSerialBelow || threads == 1) {
        lsdSortBits(data.begin(), data.end(), scratch.begin(), first_bit, key_bits);
        return;
    }
    const std::size_t grain = grainFor(n, threads, 2, 1024, std::size_t(1) << 30);
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
    std::vector<std::array<std::size_t, 256>> counts(chunks);
    for (int shift = first_bit; shift < key_bits; shift += 8) {
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
// Bits below `first_bit` are not sorted by (as parallelRadixSort: the input must already
// ascend in them).
void parallelSortKeys(Executor& executor, Buffer<std::uint64_t>& io_keys, Buffer<std::uint64_t>& scratch, int key_bits,
                      int first_bit = 0);

}  // namespace vkcollide::narrow
